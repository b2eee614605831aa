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
    let want: Vec<f64> =
        [[0.5, -1.25, 2.75], [-300.125, 17.0, 0.001]].iter().map(|p| noiselab::Noise::get(&n, *p)).collect();
    let got: Vec<f64> = text.lines().map(|l| l.parse().unwrap()).collect();
    assert_eq!(got, want);
}

#[test]
fn sample_classic_f32_matches_the_1985_program() {
    // First row of classic1985_2d.csv (Perlin's verbatim float C code).
    let out = noiselab()
        .args(["sample", "classic", "--dims", "2", "--precision", "f32"])
        .write_stdin("-102.15499877929688,-41.161708831787109\n")
        .output()
        .unwrap();
    let got: f32 = String::from_utf8(out.stdout).unwrap().trim().parse().unwrap();
    assert_eq!(got as f64, -0.17061978578567505);
}

#[test]
fn sample_f32_and_dims() {
    let out = noiselab()
        .args(["sample", "value", "--dims", "2", "--precision", "f32", "--seed", "4"])
        .write_stdin("0.5,0.5\n")
        .output()
        .unwrap();
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

#[test]
fn analyze_reports_text_json_and_plots() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.npy");
    let b = dir.path().join("b.f32");
    for (seed, path) in [("1", &a), ("2", &b)] {
        let out = noiselab()
            .args(["render", "improved", "--seed", seed, "--size", "256x256", "--scale", "16", "--slice", "0", "-o"])
            .arg(path)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", stderr_of(&out));
    }
    // Two seeds, two formats, one report; the plots folder is created.
    let plots = dir.path().join("plots");
    let out =
        noiselab().arg("analyze").args([&a, &b]).args(["--lattice", "16", "--plots"]).arg(&plots).output().unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("2 fields") && text.contains("node value score") && text.contains("null"), "{text}");
    for name in ["spectrum.png", "radial.png", "histogram.png", "folded-variance.png"] {
        let file = fs::File::open(plots.join(name)).unwrap();
        png::Decoder::new(std::io::BufReader::new(file)).read_info().unwrap();
    }
    // JSON: the documented fields, with values (gradient noise is 0 at its nodes).
    let out = noiselab().arg("analyze").arg(&a).args(["--lattice", "16", "--period", "64", "--json"]).output().unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["lattice"]["node_value_score"], 0.0);
    assert!(json["values"]["std"].as_f64().unwrap() > 0.1);
    assert!(json["spectrum"]["peak_frequency"].as_f64().unwrap() > 0.0);
    assert!(json["lattice"]["folded_variance"]["folded_variance_cv"].as_f64().unwrap() > 0.2);
    assert!(json["cyclostationarity"]["cyclo_max_over_null"].as_f64().unwrap() > 2.0);
    assert!(json["periodicity"]["x"]["rms_ratio"].as_f64().unwrap() > 0.5);
}

#[test]
fn analyze_rejects_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.npy");
    assert_one_line_error(&noiselab().arg("analyze").arg(&missing).output().unwrap(), "missing.npy");
    let junk = dir.path().join("junk.npy");
    fs::write(&junk, b"not numpy").unwrap();
    assert_one_line_error(&noiselab().arg("analyze").arg(&junk).output().unwrap(), "junk.npy");
    let odd = dir.path().join("odd.f32");
    fs::write(&odd, vec![0u8; 4 * 300]).unwrap();
    assert_one_line_error(&noiselab().arg("analyze").arg(&odd).output().unwrap(), "odd.f32");
    let big = dir.path().join("big.npy");
    let small = dir.path().join("small.npy");
    for (size, path) in [("64x64", &big), ("32x32", &small)] {
        noiselab().args(["render", "value", "--size", size, "-o"]).arg(path).assert().success();
    }
    assert_one_line_error(&noiselab().arg("analyze").args([&big, &small]).output().unwrap(), "differ in size");
    for bad in [["--lattice", "0"], ["--lattice", "-4"], ["--period", "0"], ["--lattice-offset", "a,b"]] {
        assert_one_line_error(&noiselab().arg("analyze").arg(&big).args(bad).output().unwrap(), bad[0]);
    }
    assert_one_line_error(&noiselab().arg("analyze").output().unwrap(), "FILES");
}

#[test]
fn report_renders_every_kind_and_the_checked_in_page_is_current() {
    let dir = tempfile::tempdir().unwrap();
    let out = noiselab().args(["report", "--size", "64", "--seeds", "1", "--out"]).arg(dir.path()).output().unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let fresh = fs::read_to_string(dir.path().join("quality.md")).unwrap();
    let labels = |page: &str| -> Vec<String> {
        page.lines()
            .filter(|l| l.starts_with("| ") && !l.starts_with("| noise") && !l.starts_with("| *"))
            .map(|l| l.split('|').nth(1).unwrap().trim().to_string())
            .collect()
    };
    let rows = labels(&fresh);
    assert!(rows.len() >= 2 * 6, "{rows:?}");
    for kind in ["classic", "improved", "simplex", "value", "modified"] {
        assert!(rows.iter().any(|r| r.starts_with(kind)), "{kind} missing from the report");
    }
    // Every picture the page names exists.
    for line in fresh.lines().filter(|l| l.contains("](quality/")) {
        for part in line.split("](").skip(1) {
            let file = part.split(')').next().unwrap();
            assert!(dir.path().join(file).exists(), "{file}");
        }
    }
    // The published page lists the same rows (regenerate it with the README's command when kinds change).
    let published = fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/quality.md")).unwrap();
    assert_eq!(
        labels(&published).iter().filter(|l| !l.starts_with("reference")).collect::<Vec<_>>(),
        rows.iter().filter(|l| !l.starts_with("reference")).collect::<Vec<_>>()
    );
}

/// Little-endian f32 payload of an `.npy` written by `render`.
fn npy_values(path: &std::path::Path) -> Vec<f32> {
    let bytes = fs::read(path).unwrap();
    let header = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    bytes[10 + header..].chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
}

#[test]
fn sparse_renders_the_same_image_by_splatting_and_gathering() {
    let dir = tempfile::tempdir().unwrap();
    for (dims, slice) in [("2", None), ("3", Some("-0.3")), ("4", Some("0.5,1.25"))] {
        let mut images = Vec::new();
        for method in ["splat", "gather"] {
            let path = dir.path().join(format!("{dims}-{method}.npy"));
            let mut cmd = noiselab();
            cmd.args(["render", "sparse", "--dims", dims, "--impulses", "12", "--size", "96x64", "--scale", "24"])
                .args(["--origin", "-1.5,-0.75", "--method", method, "-o"])
                .arg(&path);
            if let Some(s) = slice {
                cmd.args(["--slice", s]);
            }
            let out = cmd.output().unwrap();
            assert!(out.status.success(), "{}", stderr_of(&out));
            images.push(npy_values(&path));
        }
        let worst = images[0].iter().zip(&images[1]).map(|(a, b)| (a - b).abs()).fold(0f32, f32::max);
        assert!(worst < 1e-5, "{dims}D: splat and gather differ by {worst}");
    }
    // The Gaussian reference kernel, and sampling with options.
    let out = noiselab()
        .args(["sample", "sparse", "--kernel", "gaussian", "--impulses", "30"])
        .write_stdin("0.3 0.4 0.5\n")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let v: f64 = String::from_utf8(out.stdout).unwrap().trim().parse().unwrap();
    let n = noiselab::Sparse::new(0).with_impulses(30).unwrap().with_kernel(noiselab::Kernel::gaussian());
    assert_eq!(v, noiselab::Noise::get(&n, [0.3, 0.4, 0.5]));
}

#[test]
fn sparse_options_are_validated() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let run = |args: &[&str]| noiselab().args(args).arg("-o").arg(&out).output().unwrap();
    assert_one_line_error(&run(&["render", "sparse", "--impulses", "0"]), "--impulses");
    assert_one_line_error(&run(&["render", "sparse", "--impulses", "-3"]), "--impulses");
    assert_one_line_error(&run(&["render", "sparse", "--kernel", "box"]), "--kernel");
    assert_one_line_error(&run(&["render", "value", "--impulses", "10"]), "--impulses");
    assert_one_line_error(&run(&["render", "improved", "--method", "splat"]), "--method");
    assert_one_line_error(&run(&["render", "sparse", "--method", "scatter"]), "--method");
    assert!(!out.exists());
}

#[test]
fn tiled_renders_of_every_tileable_kind_have_no_seam() {
    // Two tiles side by side in each direction: the analysis periodicity at
    // the tile size is exactly 0 (no seam anywhere), and 1 px off it is not.
    let dir = tempfile::tempdir().unwrap();
    for kind in ["classic", "improved", "value", "modified", "sparse", "worley"] {
        let path = dir.path().join(format!("{kind}.npy"));
        let out = noiselab()
            .args(["render", kind, "--dims", "2", "--tile", "4,3", "--scale", "16", "--size", "128x96", "-o"])
            .arg(&path)
            .output()
            .unwrap();
        assert!(out.status.success(), "{kind}: {}", stderr_of(&out));
        let values = npy_values(&path);
        for j in 0..96 {
            for i in 0..128 {
                assert_eq!(
                    values[j * 128 + i].to_bits(),
                    values[(j % 48) * 128 + i % 64].to_bits(),
                    "{kind} ({i}, {j})"
                );
            }
        }
        let out = noiselab().arg("analyze").arg(&path).args(["--period", "64", "--json"]).output().unwrap();
        assert!(out.status.success(), "{kind}: {}", stderr_of(&out));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(json["periodicity"]["x"]["max_abs_diff"], 0.0, "{kind}");
    }
    assert_one_line_error(
        &noiselab().args(["render", "simplex", "--tile", "4", "-o"]).arg(dir.path().join("s.png")).output().unwrap(),
        "not tileable",
    );
    assert_one_line_error(
        &noiselab().args(["render", "value", "--tile", "4,x", "-o"]).arg(dir.path().join("s.png")).output().unwrap(),
        "--tile",
    );
}

#[test]
fn cellular_and_fast_kinds_render() {
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["worley", "--variant", "f2-f1"][..],
        &["worley", "--variant", "cells", "--metric", "manhattan", "--jitter", "0.5"],
        &["worley", "--metric", "minkowski:3", "--dims", "3"],
        &["fast"],
    ] {
        let path = dir.path().join("out.npy");
        let out =
            noiselab().arg("render").args(args).args(["--size", "64x64", "--force", "-o"]).arg(&path).output().unwrap();
        assert!(out.status.success(), "{args:?}: {}", stderr_of(&out));
        let values = npy_values(&path);
        assert!(values.iter().all(|v| v.is_finite()) && values.iter().any(|&v| v != values[0]), "{args:?}");
    }
    let bad = dir.path().join("bad.png");
    assert_one_line_error(
        &noiselab().args(["render", "worley", "--jitter", "1.5", "-o"]).arg(&bad).output().unwrap(),
        "--jitter",
    );
    assert_one_line_error(
        &noiselab().args(["render", "worley", "--metric", "taxicab", "-o"]).arg(&bad).output().unwrap(),
        "--metric",
    );
    assert_one_line_error(
        &noiselab().args(["render", "value", "--jitter", "0.5", "-o"]).arg(&bad).output().unwrap(),
        "--jitter",
    );
}

#[test]
fn recipes_render_pictures_and_fields() {
    let dir = tempfile::tempdir().unwrap();
    for recipe in ["marble", "wood", "clouds", "flame", "planet", "stucco", "bump", "hypertexture"] {
        let png_path = dir.path().join(format!("{recipe}.png"));
        let out = noiselab().args(["render", recipe, "--size", "48x40", "-o"]).arg(&png_path).output().unwrap();
        assert!(out.status.success(), "{recipe}: {}", stderr_of(&out));
        let reader =
            png::Decoder::new(std::io::BufReader::new(fs::File::open(&png_path).unwrap())).read_info().unwrap();
        let info = reader.info();
        assert_eq!((info.width, info.height, info.color_type), (48, 40, png::ColorType::Rgb), "{recipe}");
        let npy = dir.path().join(format!("{recipe}.npy"));
        let out = noiselab()
            .args(["render", recipe, "--size", "48x40", "--base", "value", "--slice", "0.25", "-o"])
            .arg(&npy)
            .output()
            .unwrap();
        assert!(out.status.success(), "{recipe}: {}", stderr_of(&out));
        let values = npy_values(&npy);
        assert_eq!(values.len(), 48 * 40);
        assert!(
            values.iter().all(|v| v.is_finite()) && values.iter().any(|&v| v != values[0]),
            "{recipe}: flat or non-finite field"
        );
        // Deterministic: the same command gives the same field.
        let again = dir.path().join(format!("{recipe}-again.npy"));
        noiselab()
            .args(["render", recipe, "--size", "48x40", "--base", "value", "--slice", "0.25", "-o"])
            .arg(&again)
            .assert()
            .success();
        assert_eq!(npy_values(&again), values, "{recipe}");
    }
    let bad = dir.path().join("bad.png");
    assert_one_line_error(
        &noiselab().args(["render", "value", "--base", "improved", "-o"]).arg(&bad).output().unwrap(),
        "--base",
    );
    assert_one_line_error(
        &noiselab().args(["render", "marble", "--dims", "2", "-o"]).arg(&bad).output().unwrap(),
        "--dims",
    );
    assert_one_line_error(
        &noiselab()
            .args(["render", "marble", "--base", "simplex-n", "--variant", "x", "-o"])
            .arg(&bad)
            .output()
            .unwrap(),
        "variant",
    );
}

#[test]
fn fractal_options_on_the_command_line() {
    let out = noiselab()
        .args(["sample", "improved", "--octaves", "4", "--fractal", "ridged"])
        .write_stdin("0.3 0.4 0.5\n")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let v: f64 = String::from_utf8(out.stdout).unwrap().trim().parse().unwrap();
    let f = noiselab::Fractal::new(|o| noiselab::Improved::new(o.seed), 0, 4, noiselab::FractalMode::Ridged).unwrap();
    assert_eq!(v, noiselab::Noise::get(&f, [0.3, 0.4, 0.5]));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("auto.npy");
    noiselab()
        .args(["render", "value", "--dims", "2", "--octaves", "auto", "--scale", "64", "--size", "32x32", "-o"])
        .arg(&path)
        .assert()
        .success();
    assert_one_line_error(
        &noiselab().args(["sample", "value", "--octaves", "auto"]).write_stdin("0 0 0\n").output().unwrap(),
        "auto",
    );
    assert_one_line_error(
        &noiselab().args(["sample", "value", "--fractal", "ridged"]).write_stdin("0 0 0\n").output().unwrap(),
        "--octaves",
    );
    assert_one_line_error(
        &noiselab().args(["sample", "value", "--octaves", "31"]).write_stdin("0 0 0\n").output().unwrap(),
        "--octaves",
    );
    assert_one_line_error(
        &noiselab()
            .args(["sample", "value", "--octaves", "3", "--lacunarity", "1"])
            .write_stdin("0 0 0\n")
            .output()
            .unwrap(),
        "lacunarity",
    );
}

#[test]
fn gallery_renders_everything_with_its_command() {
    let dir = tempfile::tempdir().unwrap();
    let out = noiselab().args(["gallery", "--out"]).arg(dir.path()).output().unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let html = fs::read_to_string(dir.path().join("index.html")).unwrap();
    for name in [
        "classic",
        "improved",
        "simplex",
        "value",
        "modified",
        "sparse",
        "worley",
        "fast",
        "marble",
        "wood",
        "clouds",
        "flame",
        "planet",
        "stucco",
        "bump",
        "hypertexture",
        "figure1a",
        "tiled-improved",
        "fractal-ridged",
    ] {
        assert!(html.contains(name), "{name} missing from the gallery");
    }
    let images: Vec<&str> = html.split("<img src=\"").skip(1).map(|s| s.split('"').next().unwrap()).collect();
    assert!(images.len() >= 40, "{} pictures", images.len());
    for image in images {
        let file = fs::File::open(dir.path().join(image)).unwrap_or_else(|e| panic!("{image}: {e}"));
        png::Decoder::new(std::io::BufReader::new(file)).read_info().unwrap();
    }
    // Each caption's command, run again, gives the same picture.
    let caption = html.split("<code>noiselab render ").nth(1).unwrap().split("</code>").next().unwrap();
    let args: Vec<&str> = caption.split_whitespace().collect();
    let (file, render_args) = (args[args.len() - 1], &args[..args.len() - 2]);
    let again = dir.path().join("again.png");
    noiselab().arg("render").args(render_args).arg("-o").arg(&again).assert().success();
    assert_eq!(fs::read(dir.path().join(file)).unwrap(), fs::read(&again).unwrap(), "{caption}");
}

#[test]
fn animations_are_animated_pngs_and_loop_seamlessly() {
    let dir = tempfile::tempdir().unwrap();
    let apng = dir.path().join("loop.png");
    noiselab()
        .args(["render", "improved", "--frames", "8", "--loop", "--size", "32x24", "-o"])
        .arg(&apng)
        .assert()
        .success();
    let reader = png::Decoder::new(std::io::BufReader::new(fs::File::open(&apng).unwrap())).read_info().unwrap();
    assert_eq!(reader.info().animation_control.map(|a| (a.num_frames, a.num_plays)), Some((8, 0)));
    // The (frames, height, width) field: with --loop the last frame is one
    // step from the first (the blend moves a few times faster there than
    // mid-loop); without it, far apart.
    let wrap_ratio = |looped: bool| {
        let path = dir.path().join(format!("{looped}.npy"));
        let mut cmd = noiselab();
        cmd.args(["render", "value", "--frames", "8", "--time-step", "0.05", "--size", "32x24", "-o"]).arg(&path);
        if looped {
            cmd.arg("--loop");
        }
        cmd.assert().success();
        let v = npy_values(&path);
        let frame = |k: usize| &v[k * 768..(k + 1) * 768];
        let diff = |a: &[f32], b: &[f32]| a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f32>();
        diff(frame(7), frame(0)) / diff(frame(1), frame(0))
    };
    let (looped, unlooped) = (wrap_ratio(true), wrap_ratio(false));
    assert!(looped < 5.0 && unlooped > 20.0 * looped, "wrap/step: looped {looped}, unlooped {unlooped}");
    let bad = dir.path().join("bad.png");
    assert_one_line_error(
        &noiselab().args(["render", "value", "--dims", "2", "--frames", "4", "-o"]).arg(&bad).output().unwrap(),
        "--frames",
    );
    assert_one_line_error(
        &noiselab().args(["render", "value", "--frames", "1", "-o"]).arg(&bad).output().unwrap(),
        "--frames",
    );
    assert_one_line_error(&noiselab().args(["render", "value", "--loop", "-o"]).arg(&bad).output().unwrap(), "--loop");
    assert_one_line_error(
        &noiselab().args(["render", "value", "--frames", "3", "-o"]).arg(dir.path().join("a.exr")).output().unwrap(),
        "--frames",
    );
}

#[test]
fn exr_output_holds_exact_values_and_completions_and_man_page_exist() {
    let dir = tempfile::tempdir().unwrap();
    let (exr, npy) = (dir.path().join("v.exr"), dir.path().join("v.npy"));
    for path in [&exr, &npy] {
        noiselab().args(["render", "simplex", "--dims", "2", "--size", "40x30", "-o"]).arg(path).assert().success();
    }
    let a = noiselab_analysis::io::read_field(&exr, None).unwrap();
    let b = noiselab_analysis::io::read_field(&npy, None).unwrap();
    assert_eq!(a, b);
    for shell in ["bash", "zsh", "fish"] {
        let out = noiselab().args(["completions", shell]).output().unwrap();
        assert!(out.status.success() && String::from_utf8_lossy(&out.stdout).contains("gallery"), "{shell}");
    }
    let man = noiselab().arg("man").output().unwrap();
    assert!(man.status.success() && String::from_utf8_lossy(&man.stdout).contains(".TH noiselab"));
}

#[test]
fn streamed_renders_equal_in_memory_ones() {
    // 2048×2049 crosses the streaming threshold; 2048×2048 does not. The
    // shared rows are the same bits, in .npy and in PNG.
    let dir = tempfile::tempdir().unwrap();
    let (small, large) = (dir.path().join("small.npy"), dir.path().join("large.npy"));
    noiselab().args(["render", "value", "--size", "2048x2048", "--scale", "100", "-o"]).arg(&small).assert().success();
    noiselab().args(["render", "value", "--size", "2048x2049", "--scale", "100", "-o"]).arg(&large).assert().success();
    let (a, b) = (npy_values(&small), npy_values(&large));
    assert_eq!(b.len(), 2048 * 2049);
    assert_eq!(&b[..a.len()], &a[..]);
    let png_path = dir.path().join("large.png");
    noiselab()
        .args(["render", "value", "--size", "2048x2049", "--scale", "100", "--bits", "16", "-o"])
        .arg(&png_path)
        .assert()
        .success();
    let mut reader =
        png::Decoder::new(std::io::BufReader::new(fs::File::open(&png_path).unwrap())).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    reader.next_frame(&mut buf).unwrap();
    assert_eq!((reader.info().width, reader.info().height), (2048, 2049));
}

#[test]
fn ramps_and_ranges_map_values() {
    let dir = tempfile::tempdir().unwrap();
    let png_path = dir.path().join("ramp.png");
    noiselab()
        .args(["render", "simplex", "--dims", "2", "--ramp", "flame", "--range", "-0.8,0.8", "--size", "20x10", "-o"])
        .arg(&png_path)
        .assert()
        .success();
    let reader = png::Decoder::new(std::io::BufReader::new(fs::File::open(&png_path).unwrap())).read_info().unwrap();
    assert_eq!(reader.info().color_type, png::ColorType::Rgb);
    // --range changes the grey mapping, not the values.
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
    noiselab().args(["render", "value", "--size", "16x16", "-o"]).arg(&a).assert().success();
    noiselab().args(["render", "value", "--size", "16x16", "--range", "-0.5,0.5", "-o"]).arg(&b).assert().success();
    assert_ne!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
    let bad = dir.path().join("bad.npy");
    assert_one_line_error(
        &noiselab().args(["render", "value", "--ramp", "wood", "-o"]).arg(&bad).output().unwrap(),
        "--ramp",
    );
    assert_one_line_error(
        &noiselab().args(["render", "value", "--range", "2,1", "-o"]).arg(&bad).output().unwrap(),
        "--range",
    );
}

#[test]
fn volumes_render_as_npy_and_numbered_slices() {
    let dir = tempfile::tempdir().unwrap();
    let npy = dir.path().join("vol.npy");
    noiselab()
        .args(["render", "improved", "--depth", "5", "--size", "12x8", "--scale", "4", "-o"])
        .arg(&npy)
        .assert()
        .success();
    let bytes = fs::read(&npy).unwrap();
    assert!(String::from_utf8_lossy(&bytes[..80]).contains("(5, 8, 12)"));
    let v = npy_values(&npy);
    // Voxel (x, y, z) = noise(x/4, y/4, z/4), z slowest.
    let n = noiselab::Improved::new(0);
    for (x, y, z) in [(0, 0, 0), (11, 7, 4), (3, 5, 2)] {
        let want = noiselab::Noise::get_f32(&n, [x as f32 / 4.0, y as f32 / 4.0, z as f32 / 4.0]);
        assert_eq!(v[z * 96 + y * 12 + x], want, "({x}, {y}, {z})");
    }
    let png_path = dir.path().join("slice.png");
    noiselab().args(["render", "improved", "--depth", "3", "--size", "12x8", "-o"]).arg(&png_path).assert().success();
    for k in 0..3 {
        assert!(dir.path().join(format!("slice-{k:03}.png")).exists());
    }
    // Nothing is overwritten without --force, and nothing half-written.
    assert_one_line_error(
        &noiselab()
            .args(["render", "improved", "--depth", "3", "--size", "12x8", "-o"])
            .arg(&png_path)
            .output()
            .unwrap(),
        "exists",
    );
    assert_one_line_error(
        &noiselab()
            .args(["render", "value", "--dims", "2", "--depth", "3", "-o"])
            .arg(dir.path().join("x.npy"))
            .output()
            .unwrap(),
        "--depth",
    );
}

#[test]
fn sample_covers_recipes() {
    let out = noiselab().args(["sample", "marble"]).write_stdin("0.1 0.2 0.3\n").output().unwrap();
    assert!(out.status.success(), "{}", stderr_of(&out));
    let v: f64 = String::from_utf8(out.stdout).unwrap().trim().parse().unwrap();
    // marble's frame: p = (3u, 3v, t) over improved noise.
    assert_eq!(v, noiselab::recipes::marble(&noiselab::Improved::new(0), [0.1 * 3.0, 0.2 * 3.0, 0.3]));
    let out = noiselab()
        .args(["sample", "hypertexture", "--base", "value"])
        .write_stdin("0.5,0.5,0\n0.01,0.01,0\n")
        .output()
        .unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    let values: Vec<f64> = text.lines().map(|l| l.parse().unwrap()).collect();
    assert!(values[0] > 0.9 && values[1] < 0.1, "{values:?}");
    assert_one_line_error(&noiselab().args(["sample", "marble"]).write_stdin("0.5 0.5\n").output().unwrap(), "line 1");
}

/// Peak resident memory of one run of the binary (Linux: wait4's rusage).
#[cfg(target_os = "linux")]
#[allow(clippy::zombie_processes)] // reaped by wait4, which also reports its rusage
fn peak_rss_kb(args: &[&str]) -> i64 {
    let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("noiselab")).args(args).spawn().unwrap();
    let mut status = 0;
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: waits for our own child; `usage` is a valid rusage to fill.
    let pid = unsafe { libc::wait4(child.id() as libc::pid_t, &mut status, 0, &mut usage) };
    assert_eq!(pid, child.id() as libc::pid_t);
    assert_eq!(status, 0, "render failed");
    usage.ru_maxrss
}

#[test]
#[cfg(target_os = "linux")]
fn large_renders_stream_in_bounded_memory() {
    // 8192×4096 f32 values alone are 128 MiB; streamed, the whole process
    // stays far below that.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.png");
    let peak = peak_rss_kb(&[
        "render",
        "value",
        "--dims",
        "2",
        "--size",
        "8192x4096",
        "--bits",
        "16",
        "-o",
        out.to_str().unwrap(),
    ]);
    eprintln!("8192x4096 16-bit PNG: peak RSS {} MiB", peak / 1024);
    assert!(peak < 64 * 1024, "peak RSS {peak} KiB");
}
