//! Reads an NC program with the reader (`crate/src/nc/reader`) and prints what it found; with
//! `--generate N FILE` first writes an ISO program of N spiral blocks to FILE. The figures of
//! the reader's time and memory come from this, run under `/usr/bin/time -v`:
//!
//! ```text
//! cargo run --release --example nc_read -- --generate 10000000 /tmp/big.ngc
//! /usr/bin/time -v target/release/examples/nc_read /tmp/big.ngc
//! ```
//!
//! The program is streamed from disk (a [`spiralcam::nc::reader::StreamSource`]); called
//! programs are looked for beside it ([`spiralcam::nc::reader::files_beside`]).

use spiralcam::nc::reader::{EventKind, Program, Reader, ReaderOptions, Step, files_beside};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.as_slice() {
        [flag, n, path] if flag == "--generate" => n
            .parse::<u64>()
            .map_err(|e| format!("{n}: {e}"))
            .and_then(|n| generate(n, Path::new(path)).map_err(|e| format!("{path}: {e}"))),
        [path] => read(Path::new(path), false),
        [path, flag] if flag == "--list" => read(Path::new(path), true),
        _ => Err("usage: nc_read PROGRAM [--list] | nc_read --generate N FILE".into()),
    };
    if let Err(e) = result {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

/// Writes an ISO program of `n` blocks: a spiral at 3600 points a revolution, 0.001 mm a turn.
fn generate(n: u64, path: &Path) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "(generated spiral, {n} blocks)")?;
    writeln!(out, "G21 G18 G90 G40 G94")?;
    writeln!(out, "G0 Z1.000000")?;
    writeln!(out, "G0 X10.000000 C0.00000")?;
    writeln!(out, "G1 Z0.000000 F50.000")?;
    writeln!(out, "G93")?;
    for k in 1..=n {
        let c = k as f64 * 0.1;
        let x = 10.0 - k as f64 * 0.001 / 3600.0;
        let z = -0.01 * (c.to_radians() * 3.0).sin();
        writeln!(out, "G1 X{x:.6} Z{z:.6} C{c:.5} F36000.000")?;
    }
    writeln!(out, "G94")?;
    writeln!(out, "G0 Z1.000000")?;
    writeln!(out, "M2")?;
    out.flush()
}

fn read(path: &Path, list: bool) -> Result<(), String> {
    let started = Instant::now();
    let program = Program::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut reader =
        Reader::new(program, ReaderOptions::default()).with_resolver(files_beside(path));
    let (mut moves, mut events) = (0u64, 0u64);
    let mut last = None;
    while let Some(step) = reader.next_step().map_err(|e| e.to_string())? {
        match step {
            Step::Move(m) => {
                moves += 1;
                if list {
                    println!(
                        "{}:{} {:?} X{:.6} Z{:.6} C{:.5} {:?}",
                        m.at.file,
                        m.at.line,
                        m.kind,
                        m.target.x(),
                        m.target.z(),
                        m.target.c(),
                        m.feed
                    );
                }
                last = Some(m);
            }
            Step::Event(e) => {
                events += 1;
                if list && !matches!(e.kind, EventKind::Comment(_)) {
                    println!("{}:{} {:?}", e.at.file, e.at.line, e.kind);
                }
            }
        }
    }
    let s = reader.summary();
    println!(
        "moves {moves}, events {events}, lines read {}",
        s.lines_read
    );
    println!(
        "units {:?}, C {:?} {:?}, X<0 {} X>0 {}, axes {}",
        s.units,
        s.c,
        s.c_range,
        s.x_negative,
        s.x_positive,
        s.axes.letters()
    );
    println!(
        "dialect {:?}: {}",
        s.dialect.dialect,
        s.dialect.evidence.join("; ")
    );
    if let Some(m) = last {
        println!(
            "last move X{:.6} Z{:.6} C{:.5} at line {}",
            m.target.x(),
            m.target.z(),
            m.target.c(),
            m.at.line
        );
    }
    println!("{:.3} s", started.elapsed().as_secs_f64());
    Ok(())
}
