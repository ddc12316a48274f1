//! Sag-with-derivatives evaluations per second for every surface family: one benchmark per
//! example job in `crate/jobs/` (data files read as the command line reads them), each
//! evaluating `Surface::local` at 10 000 points spread over the part (a sunflower pattern, so
//! every region of the surface is visited). Criterion prints the figures as elements/s.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use spiralcam::job::Job;
use std::hint::black_box;
use std::path::Path;

/// Points per iteration.
const POINTS: usize = 10_000;

/// Sunflower (Vogel) points filling a disc of `radius` evenly.
fn sunflower(radius: f64) -> Vec<(f64, f64)> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..POINTS)
        .map(|i| {
            let r = radius * ((i as f64 + 0.5) / POINTS as f64).sqrt();
            let (s, c) = (golden * i as f64).sin_cos();
            (r * c, r * s)
        })
        .collect()
}

fn evaluations(c: &mut Criterion) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .expect("crate/jobs")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();
    let mut group = c.benchmark_group("surface_local");
    group.throughput(Throughput::Elements(POINTS as u64));
    for path in paths {
        let text = std::fs::read_to_string(&path).expect("job file");
        let mut job = Job::from_json(&text).expect("valid job");
        job.load_files(|f| std::fs::read_to_string(dir.join(f)).map_err(|e| e.to_string()))
            .expect("data files");
        let surface = job
            .surface
            .build(job.part_radius_mm())
            .expect("valid surface");
        // Stay a hair inside the part: some families are undefined beyond it.
        let points = sunflower(job.part_radius_mm() * 0.999);
        group.bench_function(&job.name, |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for &(x, y) in &points {
                    let l = surface.local(x, y).expect("defined on the part");
                    sum += l.z + l.zx + l.zyy;
                }
                black_box(sum)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, evaluations);
criterion_main!(benches);
