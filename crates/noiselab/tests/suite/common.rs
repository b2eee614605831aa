//! Helpers shared by the integration tests: reading the reference CSVs.
#![allow(dead_code)]

use std::path::PathBuf;

/// One row of a reference file: the point (length = dims) and the value.
#[derive(Clone, Debug)]
pub struct Row {
    pub p: Vec<f64>,
    pub value: f64,
}

/// Path of a fixture file.
pub fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(name)
}

/// Read a `dims,x,y,z,w,value` reference file (see tests/fixtures/SOURCES.md).
pub fn read_reference(name: &str) -> Vec<Row> {
    let text = std::fs::read_to_string(fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut rows = Vec::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let dims: usize = f[0].parse().unwrap();
        let p = f[1..1 + dims].iter().map(|s| s.parse::<f64>().unwrap()).collect();
        let value = f[5].parse().unwrap();
        rows.push(Row { p, value });
    }
    assert!(rows.len() > 100, "{name}: too few rows");
    rows
}

/// Compare every row bit for bit with `eval`; on failure, report the first
/// few mismatches and the count.
pub fn assert_bit_exact(name: &str, rows: &[Row], eval: impl Fn(&[f64]) -> f64) {
    let mut bad = Vec::new();
    for r in rows {
        let got = eval(&r.p);
        if got.to_bits() != r.value.to_bits() && !(got == 0.0 && r.value == 0.0) {
            bad.push(format!("{:?}: got {got:e}, want {:e}", r.p, r.value));
        }
    }
    assert!(
        bad.is_empty(),
        "{name}: {} of {} rows differ, first: {:#?}",
        bad.len(),
        rows.len(),
        &bad[..bad.len().min(5)]
    );
}
