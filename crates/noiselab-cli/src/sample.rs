//! `noiselab sample`: points on standard input, values on standard output.

use crate::{Precision, SampleArgs};
use std::io::{BufRead, BufWriter, Write};

pub fn run(args: &SampleArgs) -> Result<(), String> {
    // A recipe reads image coordinates and time, u v t, and prints its
    // scalar field there (over its base noise, improved by default).
    let recipe = crate::recipes::find(&args.noise.kind);
    let noise = match recipe {
        Some(_) => {
            let mut base = args.noise.clone();
            base.kind = args.base.clone().unwrap_or_else(|| "improved".into());
            base.dims = Some(3);
            base
        }
        None if args.base.is_some() => return Err(format!("--base applies to recipes only, not {}", args.noise.kind)),
        None => args.noise.clone(),
    };
    let crate::Built { field, dims, .. } = noise.build(None)?;
    let dims = if recipe.is_some() { 3 } else { dims };
    let stdin = std::io::stdin();
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let io_err = |e: std::io::Error| format!("writing standard output: {e}");
    for (number, line) in stdin.lock().lines().enumerate() {
        let line = line.map_err(|e| format!("reading standard input: {e}"))?;
        let fields = split(&line);
        let result = match (recipe, &field, args.precision) {
            (Some(r), crate::registry::Field::D3(base), _) => {
                parse_point::<f64>(&fields, 3).map(|p| (r.pixel)(base, p[0], p[1], p[2]).0.to_string())
            }
            (_, _, Precision::F64) => parse_point::<f64>(&fields, dims).map(|p| field.get(&p).to_string()),
            (_, _, Precision::F32) => parse_point::<f32>(&fields, dims).map(|p| field.get_f32(&p).to_string()),
        };
        match result {
            Ok(v) => writeln!(out, "{v}").map_err(io_err)?,
            Err(why) => {
                // Values already computed stay printed; nothing after this line is.
                out.flush().map_err(io_err)?;
                return Err(format!("line {}: {why}", number + 1));
            }
        }
    }
    out.flush().map_err(io_err)
}

/// Coordinates separated by commas and/or whitespace.
pub fn split(line: &str) -> Vec<&str> {
    line.split(|c: char| c == ',' || c.is_whitespace()).filter(|s| !s.is_empty()).collect()
}

/// Exactly `dims` numbers, or an error naming the field that is not one.
pub fn parse_point<T: std::str::FromStr>(fields: &[&str], dims: usize) -> Result<Vec<T>, String> {
    if fields.len() != dims {
        return Err(format!("expected {dims} coordinates, got {}", fields.len()));
    }
    fields.iter().map(|s| s.parse::<T>().map_err(|_| format!("'{s}' is not a number"))).collect()
}
