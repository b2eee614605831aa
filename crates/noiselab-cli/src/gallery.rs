//! `noiselab gallery`: every kind, variant, fractal and recipe rendered into
//! one folder with an `index.html` naming each picture, the exact command
//! that reproduces it, and its render time. Each picture is made by parsing
//! and running that very command, so the commands cannot drift.

use std::fmt::Write as _;
use std::time::Instant;

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};

use crate::output::Pending;
use crate::{Cli, Command, GalleryArgs};

/// One picture: a title and the `render` arguments after the output path.
struct Entry {
    title: String,
    file: String,
    args: Vec<String>,
}

fn entry(title: &str, file: &str, args: &str) -> Entry {
    Entry {
        title: title.into(),
        file: format!("{file}.png"),
        args: args.split_whitespace().map(String::from).collect(),
    }
}

/// Everything the gallery shows, driven by the registries.
fn entries() -> Vec<Entry> {
    let mut list = Vec::new();
    for k in crate::registry::KINDS {
        let planes: &[f64] = if k.default_dims >= 3 { &[0.0, 0.5] } else { &[] };
        if planes.is_empty() {
            list.push(entry(k.name, k.name, &format!("{} --size 256x256 --scale 32", k.name)));
        }
        for z in planes {
            let title = format!("{}, slice z = {z}", k.name);
            list.push(entry(
                &title,
                &format!("{}-z{z}", k.name),
                &format!("{} --size 256x256 --scale 32 --slice {z}", k.name),
            ));
        }
        for (variant, what) in k.variants.iter().skip(1) {
            let slice = if k.default_dims >= 3 { " --slice 0.5" } else { "" };
            list.push(entry(
                &format!("{} --variant {variant}: {what}", k.name),
                &format!("{}-{variant}", k.name),
                &format!("{} --variant {variant} --size 256x256 --scale 32{slice}", k.name),
            ));
        }
    }
    list.push(entry(
        "sparse convolution, Gaussian reference (Frisvad & Wyvill Figure 1a)",
        "figure1a",
        "sparse --dims 2 --kernel gaussian --impulses 30 --size 512x512 --scale 32",
    ));
    list.push(entry(
        "sparse convolution, cubic kernel (Figure 1b)",
        "figure1b",
        "sparse --dims 2 --impulses 30 --size 512x512 --scale 32",
    ));
    for n in [10, 20, 30] {
        list.push(entry(
            &format!("sparse convolution, {n} impulses per cell (Figure 7)"),
            &format!("sparse-n{n}"),
            &format!("sparse --impulses {n} --size 256x256 --scale 32 --slice 0.5"),
        ));
    }
    list.push(entry(
        "improved noise tiled every 4 cells, shown 2×2: no seams",
        "tiled-improved",
        "improved --dims 2 --tile 4,4 --size 256x256 --scale 32",
    ));
    list.push(entry(
        "cellular F2 − F1 tiled every 3 cells, shown 2×2",
        "tiled-worley",
        "worley --variant f2-f1 --tile 3,3 --size 192x192 --scale 32",
    ));
    list.push(entry(
        "sparse convolution tiled every 4 cells, shown 2×2",
        "tiled-sparse",
        "sparse --dims 2 --tile 4,4 --size 256x256 --scale 32",
    ));
    for mode in noiselab::FractalMode::ALL {
        list.push(entry(
            &format!("{} of improved noise, octaves from the pixel size", mode.name()),
            &format!("fractal-{}", mode.name()),
            &format!("improved --octaves auto --fractal {} --size 256x256 --scale 64 --slice 0.5", mode.name()),
        ));
    }
    list.push(entry(
        "a seamless loop: 3D improved noise animated along z (animated PNG)",
        "loop-improved",
        "improved --frames 48 --loop --time-step 0.04 --size 192x192 --scale 48 --slice 0",
    ));
    list.push(entry(
        "a seamless loop of sparse convolution noise",
        "loop-sparse",
        "sparse --frames 48 --loop --time-step 0.04 --size 192x192 --scale 48 --slice 0",
    ));
    for r in crate::recipes::RECIPES {
        list.push(entry(&format!("{}: {}", r.name, r.summary), r.name, &format!("{} --size 256x256", r.name)));
    }
    list
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

pub fn run(args: &GalleryArgs) -> Result<(), String> {
    let dir = &args.out;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create the gallery folder: {e}", dir.display()))?;
    let list = entries();
    let bar = ProgressBar::new(list.len() as u64);
    bar.set_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}").map_err(|e| e.to_string())?);
    let started = Instant::now();
    let mut rows = String::new();
    for e in &list {
        bar.set_message(e.file.clone());
        let command = format!("noiselab render {} -o {}", e.args.join(" "), e.file);
        let path = dir.join(&e.file);
        let argv = ["noiselab", "render"].into_iter().map(String::from).chain(e.args.iter().cloned()).chain([
            "--force".into(),
            "-o".into(),
            path.display().to_string(),
        ]);
        let cli = Cli::try_parse_from(argv).map_err(|err| format!("gallery entry '{command}': {err}"))?;
        let Command::Render(render_args) = cli.command else { unreachable!("parsed a render command") };
        let t = Instant::now();
        crate::render::run(&render_args).map_err(|err| format!("gallery entry '{command}': {err}"))?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let _ = writeln!(
            rows,
            "<figure><img src=\"{}\" alt=\"{}\"><figcaption><b>{}</b><br><code>{}</code><br>{ms:.0} ms</figcaption></figure>",
            e.file,
            escape(&e.title),
            escape(&e.title),
            escape(&command)
        );
        bar.inc(1);
    }
    bar.finish_and_clear();
    let total = started.elapsed().as_secs_f64();
    let html = format!(
        "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>noiselab gallery</title>\n<style>\
         body{{font-family:sans-serif;background:#111;color:#ddd;margin:2em}}figure{{display:inline-block;width:300px;\
         vertical-align:top;margin:0 1em 2em 0}}img{{max-width:300px;image-rendering:pixelated}}code{{color:#9cf;\
         font-size:80%;word-break:break-all}}</style></head><body>\n<h1>noiselab gallery</h1>\n<p>{} pictures in {total:.1} s. \
         Every caption's command reproduces its picture exactly.</p>\n{rows}</body></html>\n",
        list.len()
    );
    Pending::create(&dir.join("index.html"), true)?.finish(|w| w.write_all(html.as_bytes()))?;
    eprintln!("{} pictures in {total:.1} s: {}", list.len(), dir.join("index.html").display());
    Ok(())
}
