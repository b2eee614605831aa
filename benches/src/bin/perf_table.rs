//! Turns the `peers` benchmark's criterion results into one markdown table.
//!
//! ```text
//! cargo bench --manifest-path benches/Cargo.toml --bench peers
//! cargo run --release --manifest-path benches/Cargo.toml --bin perf_table [-- OPTIONS]
//! ```
//!
//! Reads every `<criterion>/<group>/<function>/new/{estimates,benchmark}.json`
//! (criterion's `median` point estimate, ns per iteration, divided by the
//! elements per iteration from `benchmark.json`'s `throughput`) and prints a
//! table: one row per workload, ns/sample for `noiselab` and each peer, and
//! in parentheses each peer's time over noiselab's (> 1: noiselab is faster).
//! The fastest entry of each row is bold; a missing one is "—". Function ids
//! starting with `noiselab` other than `noiselab` itself (`noiselab-fast`,
//! …) get a second table, one column each.
//!
//! Options:
//! * `--write PATH`: also write a page (machine, command, date, tables) to
//!   PATH, relative to the repository root unless absolute;
//! * `--criterion DIR`: where criterion's results are (default
//!   `$CARGO_TARGET_DIR/criterion`, else `benches/target/criterion`);
//! * `--command CMD`: the benchmark command to record on the page (default
//!   the plain `cargo bench` line of the peers benchmark).

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::{SystemTime, UNIX_EPOCH};

use serde_json::Value;

/// The reference column.
const OURS: &str = "noiselab";

/// Peer columns, in order (ids as in `benches/peers.rs`).
const PEERS: &[&str] = &[
    "noise-rs",
    "fastnoise-lite",
    "simdnoise",
    "libnoise",
    "quick-noise",
    "quick-noise-batch",
    "noise-functions",
    "noiz",
];

/// Workloads, in row order, with a description.
const WORKLOADS: &[(&str, &str)] = &[
    ("2d_perlin", "2D Perlin, 2048² grid"),
    ("2d_simplex", "2D simplex, 2048² grid"),
    ("2d_value", "2D value, 2048² grid"),
    ("2d_cellular_f1", "2D cellular F1, 2048² grid"),
    ("2d_fbm6", "2D fBm, 6 octaves, 2048² grid"),
    ("2d_perlin_tiles", "2D Perlin, 2048² as 4096 tiles of 32²"),
    ("2d_fbm6_tiles", "2D fBm, 6 octaves, 2048² as 4096 tiles of 32²"),
    ("3d_perlin", "3D Perlin, 256³ grid"),
    ("3d_simplex", "3D simplex, 256³ grid"),
    ("3d_perlin_points", "3D Perlin, 4M random points"),
    ("scalar_f64_3d_perlin_grid", "scalar `f64` 3D Perlin, 256³ grid"),
    ("scalar_f64_3d_perlin_points", "scalar `f64` 3D Perlin, 4M random points"),
    ("2d_sparse", "2D sparse convolution (20 impulses/cell), 2048² grid"),
    ("3d_fast_texture", "3D fast volume-texture noise, 256³ grid"),
];

const BENCH_COMMAND: &str = "cargo bench --manifest-path benches/Cargo.toml --bench peers";
const TABLE_COMMAND: &str = "cargo run --release --manifest-path benches/Cargo.toml --bin perf_table";

/// One criterion benchmark's result.
#[derive(Clone, Debug, PartialEq)]
struct Entry {
    group: String,
    function: String,
    /// Median ns per iteration / elements per iteration.
    ns_per_sample: f64,
    /// When criterion wrote it.
    written: SystemTime,
}

/// Reads every `…/new/estimates.json` + `benchmark.json` pair under `root`.
fn load(root: &Path) -> Result<Vec<Entry>, String> {
    let mut dirs = Vec::new();
    find_new_dirs(root, &mut dirs).map_err(|e| format!("{}: {e}", root.display()))?;
    let mut entries = Vec::new();
    for dir in dirs {
        entries.push(read_entry(&dir)?);
    }
    entries.sort_by(|a, b| (&a.group, &a.function).cmp(&(&b.group, &b.function)));
    Ok(entries)
}

fn find_new_dirs(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    for item in fs::read_dir(dir)? {
        let path = item?.path();
        if !path.is_dir() {
            continue;
        }
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if name == "new" {
            if path.join("estimates.json").is_file() && path.join("benchmark.json").is_file() {
                out.push(path);
            }
        } else if name != "report" && name != "base" && name != "change" {
            find_new_dirs(&path, out)?;
        }
    }
    Ok(())
}

fn read_json(path: &Path) -> Result<Value, String> {
    let text = fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

fn read_entry(new_dir: &Path) -> Result<Entry, String> {
    let bench_path = new_dir.join("benchmark.json");
    let est_path = new_dir.join("estimates.json");
    let bench = read_json(&bench_path)?;
    let est = read_json(&est_path)?;
    let field = |v: &Value, key: &str| v.get(key).and_then(Value::as_str).map(str::to_owned);
    let group = field(&bench, "group_id").ok_or_else(|| format!("{}: no group_id", bench_path.display()))?;
    let mut function = field(&bench, "function_id").unwrap_or_default();
    if let Some(value) = field(&bench, "value_str") {
        function = if function.is_empty() { value } else { format!("{function}/{value}") };
    }
    let elements = match bench.get("throughput") {
        Some(Value::Object(t)) => t.get("Elements").and_then(Value::as_u64),
        _ => None,
    }
    .ok_or_else(|| format!("{}: no throughput Elements (use Throughput::Elements)", bench_path.display()))?;
    let median = est
        .get("median")
        .and_then(|m| m.get("point_estimate"))
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("{}: no median.point_estimate", est_path.display()))?;
    let written = fs::metadata(&est_path).and_then(|m| m.modified()).unwrap_or(UNIX_EPOCH);
    Ok(Entry { group, function, ns_per_sample: median / elements.max(1) as f64, written })
}

/// Three significant digits, never in exponent form.
fn sig3(x: f64) -> String {
    if !x.is_finite() {
        return "—".into();
    }
    let digits = if x >= 100.0 {
        0
    } else if x >= 10.0 {
        1
    } else if x >= 1.0 {
        2
    } else if x >= 0.1 {
        3
    } else {
        4
    };
    format!("{x:.digits$}")
}

/// The results as (group → function → ns/sample), limited to the groups that
/// hold a noiselab or known-peer function, plus the row order.
struct Results {
    rows: Vec<String>,
    by_group: BTreeMap<String, BTreeMap<String, f64>>,
}

impl Results {
    fn new(entries: &[Entry]) -> Results {
        let mut by_group: BTreeMap<String, BTreeMap<String, f64>> = BTreeMap::new();
        for e in entries {
            by_group.entry(e.group.clone()).or_default().insert(e.function.clone(), e.ns_per_sample);
        }
        by_group.retain(|_, fs| fs.keys().any(|f| f.starts_with(OURS) || PEERS.contains(&f.as_str())));
        let known = WORKLOADS.iter().map(|w| w.0);
        let mut rows: Vec<String> = known.filter(|g| by_group.contains_key(*g)).map(str::to_owned).collect();
        rows.extend(by_group.keys().filter(|g| !WORKLOADS.iter().any(|w| w.0 == g.as_str())).cloned());
        Results { rows, by_group }
    }

    fn get(&self, group: &str, function: &str) -> Option<f64> {
        self.by_group.get(group)?.get(function).copied()
    }

    /// Function ids in the included groups that are neither ours nor known peers.
    fn other_peers(&self) -> Vec<String> {
        let all: BTreeSet<&String> = self.by_group.values().flat_map(|fs| fs.keys()).collect();
        all.into_iter().filter(|f| !f.starts_with(OURS) && !PEERS.contains(&f.as_str())).cloned().collect()
    }

    /// `noiselab-…` ids (not `noiselab` itself).
    fn variants(&self) -> Vec<String> {
        let all: BTreeSet<&String> = self.by_group.values().flat_map(|fs| fs.keys()).collect();
        all.into_iter().filter(|f| f.starts_with(OURS) && f.as_str() != OURS).cloned().collect()
    }
}

fn row_label(group: &str) -> String {
    match WORKLOADS.iter().find(|w| w.0 == group) {
        Some((_, what)) => format!("{what} (`{group}`)"),
        None => format!("`{group}`"),
    }
}

/// A cell: ns/sample, the ratio in parentheses, bold if the row's fastest.
fn cell(ns: Option<f64>, ratio_to: Option<f64>, fastest: f64) -> String {
    let Some(ns) = ns else { return "—".into() };
    let mut s = sig3(ns);
    if let Some(base) = ratio_to {
        let _ = write!(s, " ({}×)", sig3(ns / base));
    }
    if ns <= fastest {
        s = format!("**{s}**");
    }
    s
}

fn header(out: &mut String, first: &str, columns: &[String]) {
    let _ = writeln!(out, "| {first} | {} |", columns.join(" | "));
    let _ = writeln!(out, "|---|{}", "---:|".repeat(columns.len()));
}

/// The markdown table(s).
fn tables(entries: &[Entry]) -> String {
    let r = Results::new(entries);
    let mut out = String::new();
    if r.rows.is_empty() {
        out.push_str("(no noiselab or peer results found)\n");
        return out;
    }

    let mut peers: Vec<String> = PEERS.iter().map(|p| p.to_string()).collect();
    peers.extend(r.other_peers());
    let mut columns = vec![format!("`{OURS}`")];
    columns.extend(peers.iter().map(|p| format!("`{p}`")));
    header(&mut out, "workload (ns/sample; in parentheses: peer / noiselab)", &columns);
    for g in &r.rows {
        let ours = r.get(g, OURS);
        let values: Vec<Option<f64>> = std::iter::once(ours).chain(peers.iter().map(|p| r.get(g, p))).collect();
        let fastest = values.iter().flatten().copied().fold(f64::INFINITY, f64::min);
        let mut cells = vec![cell(ours, None, fastest)];
        cells.extend(values[1..].iter().map(|&v| cell(v, ours, fastest)));
        let _ = writeln!(out, "| {} | {} |", row_label(g), cells.join(" | "));
    }

    let variants = r.variants();
    let rows: Vec<&String> = r.rows.iter().filter(|g| variants.iter().any(|v| r.get(g, v).is_some())).collect();
    if !rows.is_empty() {
        out.push('\n');
        let mut columns = vec![format!("`{OURS}`")];
        columns.extend(variants.iter().map(|v| format!("`{v}`")));
        columns.push("fastest peer".into());
        header(&mut out, "workload (ns/sample; in parentheses: variant / noiselab)", &columns);
        for g in rows {
            let ours = r.get(g, OURS);
            let values: Vec<Option<f64>> = std::iter::once(ours).chain(variants.iter().map(|v| r.get(g, v))).collect();
            let fastest = values.iter().flatten().copied().fold(f64::INFINITY, f64::min);
            let mut cells = vec![cell(ours, None, fastest)];
            cells.extend(values[1..].iter().map(|&v| cell(v, ours, fastest)));
            let best_peer = peers
                .iter()
                .filter_map(|p| r.get(g, p).map(|ns| (p, ns)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map_or("—".to_string(), |(p, ns)| format!("{} (`{p}`)", sig3(ns)));
            cells.push(best_peer);
            let _ = writeln!(out, "| {} | {} |", row_label(g), cells.join(" | "));
        }
    }
    out
}

// ------------------------------------------------------------ the page

/// Civil date (UTC) of a time, "YYYY-MM-DD HH:MM UTC".
fn utc(t: SystemTime) -> String {
    let secs = t.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Howard Hinnant's civil_from_days.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02} {:02}:{:02} UTC", rem / 3600, rem % 3600 / 60)
}

/// A command's stdout, run in the repository root (so `rustc` is the
/// toolchain the repository's builds use).
fn command_output(program: &str, args: &[&str]) -> Option<String> {
    let out = Command::new(program).args(args).current_dir(repo_root()).output().ok()?;
    out.status.success().then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The machine, as markdown table rows.
fn machine() -> String {
    let cpuinfo = fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let first = |key: &str| {
        cpuinfo
            .lines()
            .find(|l| l.split(':').next().is_some_and(|k| k.trim() == key))
            .and_then(|l| l.split_once(':'))
            .map(|(_, v)| v.trim().to_owned())
    };
    let mut rows = String::new();
    let mut row = |k: &str, v: String| {
        let _ = writeln!(rows, "| {k} | {v} |");
    };
    row("CPU", first("model name").map_or("unknown".into(), |m| format!("`{m}`")));
    let logical = cpuinfo.lines().filter(|l| l.starts_with("processor")).count();
    let available = std::thread::available_parallelism().map_or(0, |n| n.get());
    row("cores", format!("{logical} logical CPUs in /proc/cpuinfo, {available} available to this process"));

    let lscpu = command_output("lscpu", &[]).unwrap_or_default();
    let mut caches = Vec::new();
    for name in ["L1d", "L1i", "L2", "L3"] {
        let key = format!("{name} cache:");
        if let Some(v) = lscpu.lines().find_map(|l| l.trim().strip_prefix(&key)) {
            caches.push(format!("{name} {}", v.trim()));
        }
    }
    if caches.is_empty() {
        // /sys fallback: cpu0's caches.
        for i in 0..8 {
            let dir = format!("/sys/devices/system/cpu/cpu0/cache/index{i}");
            let read = |f: &str| fs::read_to_string(format!("{dir}/{f}")).ok().map(|s| s.trim().to_owned());
            if let (Some(level), Some(kind), Some(size)) = (read("level"), read("type"), read("size")) {
                let kind = match kind.as_str() {
                    "Data" => "d",
                    "Instruction" => "i",
                    _ => "",
                };
                caches.push(format!("L{level}{kind} {size} (per core)"));
            }
        }
    }
    row("caches", if caches.is_empty() { "unknown".into() } else { caches.join(", ") });

    let flags = first("flags").unwrap_or_default();
    let flags: BTreeSet<&str> = flags.split_whitespace().collect();
    let simd: Vec<&str> = ["sse4_2", "avx", "avx2", "fma", "avx512f", "avx512bw", "avx512vl"]
        .into_iter()
        .filter(|f| flags.contains(f))
        .collect();
    row("SIMD (of interest)", if simd.is_empty() { "unknown".into() } else { simd.join(" ") });

    let meminfo = fs::read_to_string("/proc/meminfo").unwrap_or_default();
    let mem_kib = meminfo
        .lines()
        .find_map(|l| l.strip_prefix("MemTotal:"))
        .and_then(|v| v.split_whitespace().next()?.parse::<f64>().ok());
    if let Some(kib) = mem_kib {
        row("memory", format!("{:.1} GiB", kib / (1024.0 * 1024.0)));
    }
    let rustc = command_output("rustc", &["--version"]).map_or("unknown".into(), |v| format!("`{}`", v.trim()));
    row("compiler", rustc);
    rows
}

fn page(entries: &[Entry], machine_rows: &str, bench_command: &str, table_command: &str) -> String {
    let r = Results::new(entries);
    let used: Vec<&Entry> = entries.iter().filter(|e| r.by_group.contains_key(&e.group)).collect();
    let newest = used.iter().map(|e| e.written).max().unwrap_or(UNIX_EPOCH);
    let oldest = used.iter().map(|e| e.written).min().unwrap_or(UNIX_EPOCH);
    let span_h = newest.duration_since(oldest).map_or(0.0, |d| d.as_secs_f64() / 3600.0);

    let mut s = String::new();
    s.push_str("# Performance: noiselab against other noise libraries\n\n");
    s.push_str("Generated by `benches/src/bin/perf_table.rs` from criterion's results of `benches/benches/peers.rs`; ");
    s.push_str("the workloads and each peer's API are described at the top of that file.\n\n");
    s.push_str("## Machine\n\n| item | value |\n|---|---|\n");
    s.push_str(machine_rows);
    let _ = writeln!(s, "\n## Command\n\n```sh\n{bench_command}\n{table_command}\n```\n");
    let _ = writeln!(s, "Date of the criterion results: {}.\n", utc(newest));
    s.push_str("## Results\n\n");
    s.push_str(
        "ns per sample (lower is better). In parentheses: the peer's time over noiselab's, so a ratio above 1 means noiselab \
         is faster. The fastest entry of each row is bold; \"—\" means the library has no such noise (or it was not run).\n\n",
    );
    s.push_str(&tables(entries));
    s.push_str(
        "\nAll figures come from one criterion run on this machine: the median of criterion's samples (10 per benchmark), \
         single thread, divided by the samples per iteration.\n",
    );
    if span_h > 3.0 {
        let _ = writeln!(
            s,
            "\n**Note:** these results were written over {span_h:.1} hours, so they may come from more than one run."
        );
    }
    s
}

// ---------------------------------------------------------------- main

fn manifest_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn repo_root() -> PathBuf {
    manifest_dir().parent().map_or_else(manifest_dir, Path::to_path_buf)
}

fn default_criterion_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(t) => {
            let t = PathBuf::from(t);
            if t.is_absolute() { t } else { manifest_dir().join(t) }.join("criterion")
        }
        None => manifest_dir().join("target").join("criterion"),
    }
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let (mut write, mut criterion, mut bench_command) = (None, default_criterion_dir(), BENCH_COMMAND.to_string());
    while let Some(a) = args.next() {
        let mut value = |name: &str| args.next().ok_or_else(|| format!("{name} needs a value"));
        match a.as_str() {
            "--write" => write = Some(PathBuf::from(value("--write")?)),
            "--criterion" => criterion = PathBuf::from(value("--criterion")?),
            "--command" => bench_command = value("--command")?,
            "-h" | "--help" => {
                println!("usage: perf_table [--write PATH] [--criterion DIR] [--command CMD]");
                return Ok(());
            }
            other => return Err(format!("unknown argument {other:?} (see --help)")),
        }
    }
    let entries = load(&criterion)?;
    print!("{}", tables(&entries));
    if let Some(path) = write {
        let path = if path.is_absolute() { path } else { repo_root().join(path) };
        let mut table_command =
            format!("{TABLE_COMMAND} -- --write {}", path.strip_prefix(repo_root()).unwrap_or(&path).display());
        if criterion != default_criterion_dir() {
            let _ = write!(table_command, " --criterion {}", criterion.display());
        }
        let text = page(&entries, &machine(), &bench_command, &table_command);
        fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("perf_table: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fake criterion tree: (group, function, median ns/iteration, elements).
    fn fixture(name: &str, benches: &[(&str, &str, f64, u64)]) -> PathBuf {
        let root = std::env::temp_dir().join(format!("perf_table_{name}_{}", std::process::id()));
        let _ = fs::remove_dir_all(&root);
        for &(group, function, median, elements) in benches {
            let new = root.join(group).join(function).join("new");
            fs::create_dir_all(&new).unwrap();
            let bench = serde_json::json!({
                "group_id": group, "function_id": function, "value_str": null,
                "throughput": {"Elements": elements}, "full_id": format!("{group}/{function}"),
                "directory_name": format!("{group}/{function}"), "title": format!("{group}/{function}"),
            });
            let est = serde_json::json!({
                "mean": {"confidence_interval": {"confidence_level": 0.95, "lower_bound": 1.0, "upper_bound": 2.0},
                         "point_estimate": median * 1.5, "standard_error": 0.1},
                "median": {"confidence_interval": {"confidence_level": 0.95, "lower_bound": 1.0, "upper_bound": 2.0},
                           "point_estimate": median, "standard_error": 0.1},
            });
            fs::write(new.join("benchmark.json"), bench.to_string()).unwrap();
            fs::write(new.join("estimates.json"), est.to_string()).unwrap();
            // criterion's other copies must be ignored
            fs::create_dir_all(root.join(group).join(function).join("base")).unwrap();
        }
        fs::create_dir_all(root.join("report")).unwrap();
        root
    }

    #[test]
    fn parses_medians_per_element() {
        let root = fixture(
            "parse",
            &[("2d_perlin", "noiselab", 4_000_000.0, 4_000_000), ("2d_perlin", "noise-rs", 40_000_000.0, 4_000_000)],
        );
        let entries = load(&root).unwrap();
        assert_eq!(entries.len(), 2);
        assert_eq!((entries[0].group.as_str(), entries[0].function.as_str()), ("2d_perlin", "noise-rs"));
        assert_eq!(entries[0].ns_per_sample, 10.0);
        assert_eq!(entries[1].ns_per_sample, 1.0);
        fs::remove_dir_all(root).unwrap();
    }

    #[test]
    fn table_marks_fastest_ratios_and_missing() {
        let root = fixture(
            "table",
            &[
                ("2d_perlin", "noiselab", 2_000.0, 1_000),
                ("2d_perlin", "noise-rs", 9_600.0, 1_000),
                ("2d_perlin", "quick-noise", 240.0, 1_000),
                ("3d_simplex", "noiselab", 2_500.0, 1_000),
                ("3d_simplex", "simdnoise", 5_700.0, 1_000),
                ("3d_simplex", "noiselab-fast", 1_250.0, 1_000),
                ("unrelated group", "fast", 1.0, 1),
            ],
        );
        let t = tables(&load(&root).unwrap());
        let lines: Vec<&str> = t.lines().collect();
        // header, separator, two rows; blank; header, separator, one row
        assert_eq!(lines.len(), 8, "{t}");
        assert!(
            lines[0].starts_with("| workload") && lines[0].contains("| `noiselab` | `noise-rs` | `fastnoise-lite` |"),
            "{t}"
        );
        assert_eq!(lines[1], format!("|---|{}", "---:|".repeat(1 + PEERS.len())));
        assert_eq!(
            lines[2],
            "| 2D Perlin, 2048² grid (`2d_perlin`) | 2.00 | 9.60 (4.80×) | — | — | — | **0.240 (0.120×)** | — | — | — |"
        );
        assert_eq!(
            lines[3],
            "| 3D simplex, 256³ grid (`3d_simplex`) | **2.50** | — | — | 5.70 (2.28×) | — | — | — | — | — |"
        );
        assert!(!t.contains("unrelated"), "{t}");
        assert!(lines[5].contains("| `noiselab` | `noiselab-fast` | fastest peer |"), "{t}");
        assert_eq!(
            lines[7],
            "| 3D simplex, 256³ grid (`3d_simplex`) | 2.50 | **1.25 (0.500×)** | 5.70 (`simdnoise`) |"
        );
        let p = page(&load(&root).unwrap(), "| CPU | x |\n", "cargo bench X", "cargo run Y");
        assert!(
            p.contains("cargo bench X\ncargo run Y") && p.contains("| CPU | x |") && p.contains("one criterion run"),
            "{p}"
        );
        fs::remove_dir_all(root).unwrap();
    }

    #[test]
    fn formats() {
        assert_eq!(sig3(186.94), "187");
        assert_eq!(sig3(15.73), "15.7");
        assert_eq!(sig3(1.324), "1.32");
        assert_eq!(sig3(0.2412), "0.241");
        assert_eq!(sig3(0.04), "0.0400");
        assert_eq!(utc(UNIX_EPOCH + std::time::Duration::from_secs(1_795_000_000)), "2026-11-18 11:06 UTC");
    }
}
