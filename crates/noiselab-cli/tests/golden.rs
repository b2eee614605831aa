//! Golden images: a small render of every registry entry (every kind and
//! variant, the fractal modes and every recipe) compared bit for bit with
//! checked-in `.npy` references, so any change of values is a visible,
//! deliberate decision. After an intended change, regenerate with
//! `NOISELAB_BLESS=1 cargo test -p noiselab-cli --test golden` and review
//! the diff.

use assert_cmd::Command;
use std::fs;
use std::path::PathBuf;

/// (reference name, render arguments).
fn entries() -> Vec<(String, Vec<String>)> {
    let list = Command::cargo_bin("noiselab").unwrap().arg("list").output().unwrap();
    let text = String::from_utf8(list.stdout).unwrap();
    let mut out = Vec::new();
    let mut section = "";
    let mut kind = String::new();
    for line in text.lines() {
        if line.starts_with("kinds:") || line.starts_with("recipes") || line.starts_with("fractal") {
            section = if line.starts_with("kinds") {
                "kinds"
            } else if line.starts_with("recipes") {
                "recipes"
            } else {
                ""
            };
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        match section {
            "kinds" if !line.starts_with(' ') => {
                kind = words[0].to_string();
                out.push((kind.clone(), vec![kind.clone()]));
            }
            "kinds" => {
                if let Some(v) = words.get(1).filter(|_| words[0] == "--variant") {
                    let v = v.trim_end_matches(':');
                    out.push((format!("{kind}-{v}"), vec![kind.clone(), "--variant".into(), v.into()]));
                }
            }
            "recipes" => out.push((words[0].to_string(), vec![words[0].to_string()])),
            _ => {}
        }
    }
    for mode in ["fbm", "turbulence", "ridged", "billow", "hybrid"] {
        out.push((
            format!("fractal-{mode}"),
            ["value", "--octaves", "4", "--fractal", mode].map(String::from).to_vec(),
        ));
    }
    out
}

#[test]
fn every_registry_entry_matches_its_golden_image() {
    let dir = tempfile::tempdir().unwrap();
    let golden = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let bless = std::env::var_os("NOISELAB_BLESS").is_some();
    let entries = entries();
    assert!(entries.len() > 25, "{} entries", entries.len());
    let mut missing = Vec::new();
    for (name, args) in entries {
        let path = dir.path().join(format!("{name}.npy"));
        let out = Command::cargo_bin("noiselab")
            .unwrap()
            .arg("render")
            .args(&args)
            .args(["--size", "16x12", "--scale", "5", "--origin", "-1.3,0.7", "-o"])
            .arg(&path)
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}: {}", String::from_utf8_lossy(&out.stderr));
        let fresh = fs::read(&path).unwrap();
        let reference = golden.join(format!("{name}.npy"));
        if bless {
            fs::write(&reference, &fresh).unwrap();
            continue;
        }
        match fs::read(&reference) {
            Ok(want) => {
                assert!(want == fresh, "{name}: values changed (render {args:?} differs from tests/golden/{name}.npy)")
            }
            Err(_) => missing.push(name),
        }
    }
    assert!(missing.is_empty(), "no golden image for {missing:?}: bless with NOISELAB_BLESS=1");
}
