//! Planning throughput: spiral sampling, one-way compensation and ISO NC writing (into a byte
//! sink) for 1 M points on the paper 004 lens array and on an asphere; and the axis checks
//! (`axis_checks::check_axes`) of the 1 M point lens-array path against the `fts_70um_700hz`
//! example machine. Criterion prints the figures as elements (points) per second.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use spiralcam::dynamics::axis_checks::{AxisSample, check_axes};
use spiralcam::job::Job;
use spiralcam::job::machine::presets;
use spiralcam::plan::{Planner, Sinks};
use std::hint::black_box;
use std::ops::ControlFlow;

/// A job of exactly 1 000 001 points: `revs` revolutions of `1e6 / revs` points each.
fn million(job: &str, revs: f64) -> Job {
    let mut job = Job::from_json(job).expect("job");
    let radius = job.part_radius_mm();
    job.strategy.feed_mm_per_rev = radius / revs;
    job.strategy.sampling = spiralcam::job::Sampling::ConstantAngle {
        points_per_rev: (1e6 / revs) as u32,
    };
    job.output.dialect = spiralcam::job::Dialect::Iso;
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

fn axis_checks(c: &mut Criterion) {
    let job = million(include_str!("../jobs/lens-array-paper004.json"), 500.0);
    let planner = Planner::new(&job).expect("valid job");
    let samples: Vec<AxisSample> = planner
        .points()
        .map(|p| AxisSample::slide_only(&p.expect("plan")))
        .collect();
    let machine = presets()[2].machine(job.machine.spindle_rpm);
    let mut group = c.benchmark_group("check_axes_1M");
    group.sample_size(10);
    group.throughput(Throughput::Elements(samples.len() as u64));
    group.bench_function("lens_array_paper004", |b| {
        b.iter(|| black_box(check_axes(black_box(&samples), &machine)))
    });
    group.finish();
}

criterion_group!(benches, plan_and_write, axis_checks);
criterion_main!(benches);
