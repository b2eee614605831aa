//! The built `noiselab` binary, as a user meets it.

use assert_cmd::Command;
use std::fs;

fn noiselab() -> Command {
    Command::cargo_bin("noiselab").unwrap()
}

fn stderr_of(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// An error is one line on stderr and a non-zero exit status.
fn assert_one_line_error(out: &std::process::Output, needle: &str) {
    assert!(!out.status.success(), "expected failure");
    let err = stderr_of(out);
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err:?}");
    assert!(err.contains(needle), "{err:?} does not mention {needle:?}");
}

#[test]
fn sample_improved_prints_reference_value() {
    let out = noiselab().args(["sample", "improved"]).write_stdin("3.14 42 7\n3.14,42,7\n").output().unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "0.13691995878400012\n0.13691995878400012\n");
}

#[test]
fn sample_values_round_trip_exactly() {
    let input = "0.5 -1.25 2.75\n-300.125 17 0.001\n";
    let out = noiselab().args(["sample", "improved", "--variant", "2002"]).write_stdin(input).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    let n = noiselab::Improved::new(0).with_variant(noiselab::ImprovedVariant::Original2002);
    let want: Vec<f64> = [[0.5, -1.25, 2.75], [-300.125, 17.0, 0.001]].iter().map(|p| noiselab::Noise::get(&n, *p)).collect();
    let got: Vec<f64> = text.lines().map(|l| l.parse().unwrap()).collect();
    assert_eq!(got, want);
}

#[test]
fn sample_classic_f32_matches_the_1985_program() {
    // First row of classic1985_2d.csv (Perlin's verbatim float C code).
    let out = noiselab().args(["sample", "classic", "--dims", "2", "--precision", "f32"]).write_stdin("-102.15499877929688,-41.161708831787109\n").output().unwrap();
    let got: f32 = String::from_utf8(out.stdout).unwrap().trim().parse().unwrap();
    assert_eq!(got as f64, -0.17061978578567505);
}

#[test]
fn sample_f32_and_dims() {
    let out = noiselab().args(["sample", "value", "--dims", "2", "--precision", "f32", "--seed", "4"]).write_stdin("0.5,0.5\n").output().unwrap();
    let got: f32 = String::from_utf8(out.stdout).unwrap().trim().parse().unwrap();
    assert_eq!(got, noiselab::Noise::<2>::get_f32(&noiselab::Value::new(4), [0.5, 0.5]));
}

#[test]
fn sample_bad_line_names_the_line_and_stops() {
    let out = noiselab().args(["sample", "improved"]).write_stdin("1 2 3\n1 2\n4 5 6\n").output().unwrap();
    assert_one_line_error(&out, "line 2");
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 1, "nothing after the bad line");
    let out = noiselab().args(["sample", "improved"]).write_stdin("1 2 x\n").output().unwrap();
    assert_one_line_error(&out, "line 1");
}

#[test]
fn sample_rejects_bad_arguments() {
    assert_one_line_error(&noiselab().args(["sample", "nosuch"]).output().unwrap(), "unknown kind");
    assert_one_line_error(&noiselab().args(["sample", "improved", "--dims", "5"]).output().unwrap(), "--dims");
    assert_one_line_error(&noiselab().args(["sample", "classic", "--dims", "4"]).output().unwrap(), "--dims");
    assert_one_line_error(&noiselab().args(["sample", "improved", "--variant", "1999"]).output().unwrap(), "--variant");
    assert_one_line_error(&noiselab().args(["sample", "value", "--variant", "x"]).output().unwrap(), "no variants");
    assert_one_line_error(&noiselab().args(["sample", "improved", "--seed", "-1"]).output().unwrap(), "seed");
}

#[test]
fn render_npy_holds_exact_values() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("v.npy");
    let out = noiselab()
        .args(["render", "improved", "--size", "20x7", "--scale", "8", "--origin", "-1.5,2", "--slice", "0.25", "-o"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let bytes = fs::read(&path).unwrap();
    let header_len = 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert!(std::str::from_utf8(&bytes[10..header_len]).unwrap().contains("'shape': (7, 20)"));
    let values: Vec<f32> = bytes[header_len..].chunks(4).map(|c| f32::from_le_bytes(c.try_into().unwrap())).collect();
    assert_eq!(values.len(), 140);
    let n = noiselab::Improved::new(0);
    for j in 0..7 {
        for i in 0..20 {
            let p = [(-1.5 + i as f64 * 0.125) as f32, (2.0 + j as f64 * 0.125) as f32, 0.25];
            assert_eq!(values[j * 20 + i], noiselab::Noise::<3>::get_f32(&n, p), "pixel ({j}, {i})");
        }
    }
}

#[test]
fn render_png_8_and_16_bit() {
    let dir = tempfile::tempdir().unwrap();
    for (bits, depth) in [("8", png::BitDepth::Eight), ("16", png::BitDepth::Sixteen)] {
        let path = dir.path().join(format!("s{bits}.png"));
        let out = noiselab()
            .args(["render", "value", "--dims", "2", "--size", "33x17", "--bits", bits, "-o"])
            .arg(&path)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", stderr_of(&out));
        let decoder = png::Decoder::new(std::io::BufReader::new(fs::File::open(&path).unwrap()));
        let reader = decoder.read_info().unwrap();
        let info = reader.info();
        assert_eq!((info.width, info.height, info.bit_depth), (33, 17, depth));
    }
}

#[test]
fn render_never_leaves_partial_or_clobbers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.f32");
    fs::write(&path, b"keep").unwrap();
    let out = noiselab().args(["render", "value", "--size", "4x4", "-o"]).arg(&path).output().unwrap();
    assert_one_line_error(&out, "already exists");
    assert_eq!(fs::read(&path).unwrap(), b"keep");
    let out = noiselab().args(["render", "value", "--size", "4x4", "--force", "-o"]).arg(&path).output().unwrap();
    assert!(out.status.success());
    assert_eq!(fs::read(&path).unwrap().len(), 64);
    // Failures leave nothing behind, temporary files included.
    let missing = dir.path().join("no/such/dir/x.png");
    assert_one_line_error(&noiselab().args(["render", "value", "-o"]).arg(&missing).output().unwrap(), "cannot write");
    let names: Vec<_> = fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names.len(), 1, "{names:?}");
}

#[test]
fn render_rejects_bad_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("o.png");
    let run = |args: &[&str]| noiselab().arg("render").args(args).arg("-o").arg(&o).output().unwrap();
    assert_one_line_error(&run(&["nosuch"]), "unknown kind");
    assert_one_line_error(&run(&["improved", "--size", "0x5"]), "size");
    assert_one_line_error(&run(&["improved", "--size", "abc"]), "size");
    assert_one_line_error(&run(&["improved", "--scale", "0"]), "scale");
    assert_one_line_error(&run(&["improved", "--scale", "nan"]), "scale");
    assert_one_line_error(&run(&["improved", "--origin", "1"]), "pair");
    assert_one_line_error(&run(&["improved", "--dims", "2", "--slice", "1"]), "--slice");
    assert_one_line_error(&run(&["improved", "--bits", "12"]), "bits");
    assert_one_line_error(&run(&["improved", "--size", "100000x100000"]), "pixels");
    let bad_ext = dir.path().join("o.bmp");
    let out = noiselab().args(["render", "improved", "-o"]).arg(&bad_ext).output().unwrap();
    assert_one_line_error(&out, "unknown output format");
    assert!(!o.exists() && !bad_ext.exists());
}

#[test]
fn list_names_every_kind() {
    let out = noiselab().arg("list").output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    for kind in ["classic", "improved", "simplex", "simplex-n", "value", "modified"] {
        assert!(text.lines().any(|l| l.starts_with(kind)), "{kind} missing from:\n{text}");
    }
}
