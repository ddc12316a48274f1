//! Planning throughput: spiral sampling, one-way compensation and ISO NC writing (into a byte
//! sink) for 1 M points on the paper 004 lens array and on an asphere. Criterion prints the
//! figures as elements (points) per second.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use spiralcam::job::Job;
use spiralcam::plan::{Planner, Sinks};
use std::hint::black_box;
use std::ops::ControlFlow;

/// A job of exactly 1 000 001 points: `revs` revolutions of `1e6 / revs` points each.
fn million(job: &str, revs: f64) -> Job {
    let mut job = Job::from_json(job).expect("job");
    let radius = job.part_radius_mm();
    job.strategy.feed_mm_per_rev = radius / revs;
    job.strategy.sampling = spiralcam::spiral::Sampling::ConstantAngle {
        points_per_rev: (1e6 / revs) as u32,
    };
    job.output.dialect = spiralcam::nc::Dialect::Iso;
    job
}

fn plan_and_write(c: &mut Criterion) {
    let jobs = [
        (
            "lens_array_paper004",
            million(include_str!("../jobs/lens-array-paper004.json"), 500.0),
        ),
        (
            "asphere",
            million(include_str!("../jobs/asphere-f20.json"), 1000.0),
        ),
    ];
    let mut group = c.benchmark_group("plan_compensate_iso_nc_1M");
    group.sample_size(10);
    for (name, job) in &jobs {
        let planner = Planner::new(job).expect("valid job");
        group.throughput(Throughput::Elements(planner.spiral().point_count_hint()));
        group.bench_function(*name, |b| {
            b.iter(|| {
                let mut sink = std::io::sink();
                let sinks = Sinks {
                    nc: Some(&mut sink),
                    ..Default::default()
                };
                black_box(
                    planner
                        .run(sinks, &mut |_| ControlFlow::Continue(()))
                        .expect("plan"),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, plan_and_write);
criterion_main!(benches);
