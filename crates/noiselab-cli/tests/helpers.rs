//! The command line's pure helpers: NPY headers, value-to-pixel mapping,
//! argument and point parsing.

use noiselab_cli::internals::{npy_header, parse_list, parse_pair, parse_point, parse_scale, parse_size, split, unit};

#[test]
fn npy_header_is_aligned_and_parsable() {
    let h = npy_header(&[3, 5]);
    assert_eq!(h.len() % 64, 0);
    assert!(h.starts_with(b"\x93NUMPY\x01\x00"));
    let text = std::str::from_utf8(&h[10..]).unwrap();
    assert!(text.contains("'shape': (3, 5)"));
    assert!(text.ends_with('\n'));
}

#[test]
fn unit_mapping_clamps_and_handles_nan() {
    assert_eq!(unit(0.0, (-1.0, 1.0)), 0.5);
    assert_eq!(unit(5.0, (-1.0, 1.0)), 1.0);
    assert_eq!(unit(f32::NAN, (-1.0, 1.0)), 0.0);
}

#[test]
fn parses_arguments() {
    assert_eq!(parse_size("640x480").unwrap(), (640, 480));
    assert!(parse_size("0x10").is_err());
    assert!(parse_size("10").is_err());
    assert!(parse_scale("0").is_err());
    assert!(parse_scale("-3").is_err());
    assert!(parse_scale("nan").is_err());
    assert_eq!(parse_pair("1.5,-2").unwrap(), (1.5, -2.0));
    assert!(parse_pair("1").is_err());
    assert_eq!(parse_list("0.5,2").unwrap(), vec![0.5, 2.0]);
}

#[test]
fn splits_on_commas_and_spaces() {
    assert_eq!(split(" 1.5, -2  3e1\t4 "), vec!["1.5", "-2", "3e1", "4"]);
    assert_eq!(split("1,,2"), vec!["1", "2"]);
}

#[test]
fn parses_exact_counts_only() {
    assert_eq!(parse_point::<f64>(&["1", "2"], 2).unwrap(), vec![1.0, 2.0]);
    assert!(parse_point::<f64>(&["1"], 2).is_err());
    assert!(parse_point::<f64>(&["1", "x"], 2).unwrap_err().contains("'x'"));
    // NaN and infinities are numbers: the library defines their result.
    assert!(parse_point::<f64>(&["nan", "inf"], 2).is_ok());
}
