//! Work split over the machine's cores: every core natively, one thread in the browser, where
//! the module has no threads and spawning one would trap. Each item is computed alone, so a
//! result never depends on how the work was split. [`fill_chunks`] splits one slice over the
//! threads, [`map_parts`] a range of items, [`fill_each`] hands its items out one at a time,
//! [`both`] runs two stages side by side, [`read_ahead`] makes a record's next blocks while the
//! caller reads the ones before; [`pipeline`] streams batches through them in order while the
//! calling thread consumes the finished ones (a producer-consumer pipeline over
//! `std::sync::mpsc` channels).

use std::ops::Range;

/// Threads for parallel work: every core natively, one in the browser.
pub fn workers() -> usize {
    if cfg!(target_arch = "wasm32") {
        return 1;
    }
    // Asked once: the standard library reads the cgroup's quota files each time.
    static WORKERS: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *WORKERS.get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// `a()` and `b()`, `b` on a second thread while the calling thread computes `a` (one after the
/// other where there is one worker): for two independent stages of one job.
pub fn both<A, B>(a: impl FnOnce() -> A, b: impl FnOnce() -> B + Send) -> (A, B)
where
    B: Send,
{
    if workers() <= 1 {
        let first = a();
        return (first, b());
    }
    std::thread::scope(|scope| {
        let other = scope.spawn(b);
        let first = a();
        let second = other
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e));
        (first, second)
    })
}

/// Fills `out` by `fill(first, chunk)` on [`workers`] threads, each given a contiguous chunk
/// and the index of its first item; serially where there is one worker or one item. The first
/// error in item order wins.
pub fn fill_chunks<T, E>(
    out: &mut [T],
    fill: impl Fn(usize, &mut [T]) -> Result<(), E> + Sync,
) -> Result<(), E>
where
    T: Send,
    E: Send,
{
    let chunk = out.len().div_ceil(workers()).max(1);
    if chunk >= out.len() {
        return fill(0, out);
    }
    std::thread::scope(|scope| {
        let fill = &fill;
        let handles: Vec<_> = out
            .chunks_mut(chunk)
            .enumerate()
            .map(|(k, part)| scope.spawn(move || fill(k * chunk, part)))
            .collect();
        handles
            .into_iter()
            .try_for_each(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
    })
}

/// `value(i)` for every `i` in `0..n`, computed in contiguous parts on [`workers`] threads.
pub fn map_indices(n: usize, value: impl Fn(usize) -> f64 + Sync) -> Vec<f64> {
    let mut out = vec![0.0; n];
    let Ok(()) = fill_chunks(&mut out, |first, part| {
        (first..)
            .zip(part.iter_mut())
            .for_each(|(i, v)| *v = value(i));
        Ok::<(), std::convert::Infallible>(())
    });
    out
}

/// `part(range)` of `0..n` cut into one contiguous range a worker, in order (one range on one
/// worker): a pass over many items whose parts' results are then combined, as a maximum or a
/// first position, the same whichever way the items were cut.
pub fn map_parts<T: Send>(n: usize, part: impl Fn(Range<usize>) -> T + Sync) -> Vec<T> {
    let size = n.div_ceil(workers()).max(1);
    let mut out: Vec<Option<T>> = (0..n.div_ceil(size).max(1)).map(|_| None).collect();
    let Ok(()) = fill_chunks(&mut out, |first, slots| {
        for (p, slot) in (first..).zip(slots.iter_mut()) {
            *slot = Some(part(p * size..((p + 1) * size).min(n)));
        }
        Ok::<(), std::convert::Infallible>(())
    });
    out.into_iter().flatten().collect()
}

/// Fills `out[k]` with `make(k)` on [`workers`] threads, each taking the next item as it
/// finishes one (for items of uneven cost, which contiguous chunks would leave to one thread);
/// serially where there is one worker or one item. The first error in item order wins.
pub fn fill_each<T, E>(out: &mut [T], make: impl Fn(usize) -> Result<T, E> + Sync) -> Result<(), E>
where
    T: Send,
    E: Send,
{
    let (n, w) = (out.len(), workers().min(out.len()));
    if w <= 1 {
        for (k, slot) in out.iter_mut().enumerate() {
            *slot = make(k)?;
        }
        return Ok(());
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let take = || next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let done: Vec<Vec<(usize, Result<T, E>)>> = std::thread::scope(|scope| {
        let worker = || {
            // A worker stops at its first error: every item before it was taken, and is computed.
            let mut mine = Vec::new();
            loop {
                let k = take();
                if k >= n {
                    break mine;
                }
                let r = make(k);
                let failed = r.is_err();
                mine.push((k, r));
                if failed {
                    break mine;
                }
            }
        };
        let handles: Vec<_> = (0..w).map(|_| scope.spawn(worker)).collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    let mut first_error: Option<(usize, E)> = None;
    for (k, r) in done.into_iter().flatten() {
        match r {
            Ok(v) => out[k] = v,
            Err(e) if first_error.as_ref().is_none_or(|(j, _)| k < *j) => {
                first_error = Some((k, e))
            }
            Err(_) => {}
        }
    }
    first_error.map_or(Ok(()), |(_, e)| Err(e))
}

/// Reads a record of `n` items that `fill(first, block)` makes a block at a time (`block` items
/// from `first`, the last shorter): `read` is handed a source `next(first, out)` that copies the
/// items `first …` into `out`, asked for in order from 0. Where there are two workers the blocks
/// are made on a second thread, up to two ahead of the reader, while the reader works through
/// the ones before (a serial pass over a record beside the record's making); else each as it is
/// asked for. The items are `fill`'s either way (each computed alone); a reader that stops early
/// stops the making.
pub fn read_ahead<T, R>(
    n: usize,
    block: usize,
    fill: impl Fn(usize, &mut [T]) + Sync,
    read: impl FnOnce(&mut dyn FnMut(usize, &mut [T])) -> R,
) -> R
where
    T: Copy + Default + Send,
{
    let block = block.max(1);
    if workers() <= 1 || n <= block {
        return read(&mut |first, out| fill(first, out));
    }
    std::thread::scope(|scope| {
        let (made, take) = std::sync::mpsc::sync_channel::<Vec<T>>(1);
        let (spent, reuse) = std::sync::mpsc::channel::<Vec<T>>();
        let fill = &fill;
        scope.spawn(move || {
            for first in (0..n).step_by(block) {
                let mut buffer = reuse.try_recv().unwrap_or_default();
                buffer.clear();
                buffer.resize(block.min(n - first), T::default());
                fill(first, &mut buffer);
                if made.send(buffer).is_err() {
                    return; // the reader is done
                }
            }
        });
        let (mut current, mut at, mut next) = (Vec::new(), 0, 0);
        let mut source = move |first: usize, out: &mut [T]| {
            assert_eq!(first, next, "read_ahead: the items are read in order");
            let mut done = 0;
            while done < out.len() {
                if at == current.len() {
                    let Ok(fresh) = take.recv() else {
                        panic!("read_ahead: items past the record's {n} asked for");
                    };
                    let _ = spent.send(std::mem::replace(&mut current, fresh));
                    at = 0;
                }
                let k = (current.len() - at).min(out.len() - done);
                out[done..done + k].copy_from_slice(&current[at..at + k]);
                (at, done) = (at + k, done + k);
            }
            next += out.len();
        };
        read(&mut source)
    })
}

/// Streams batches of items through [`workers`] threads, handing the results on in order:
/// `fill` refills an input batch on the calling thread (left empty: no more), `work(first,
/// input, output)` computes a batch on a worker (`first` the index of its first item), and
/// `consume` takes the outputs in order on the calling thread while the workers compute the
/// next batches. At most `workers + 1` batches are in flight, so memory stays bounded; buffers
/// are reused. With one worker (the browser) everything runs on the calling thread. The first
/// error in order wins and stops the pipeline.
pub fn pipeline<I, O, E>(
    fill: impl FnMut(&mut Vec<I>),
    work: impl Fn(u64, &[I], &mut Vec<O>) -> Result<(), E> + Sync,
    consume: impl FnMut(&[O]) -> Result<(), E>,
) -> Result<(), E>
where
    I: Send,
    O: Send,
    E: Send,
{
    pipeline_on(workers(), fill, work, consume)
}

/// [`pipeline`] on `w` threads (at least one): 1 where `work` itself shares each batch out
/// over the cores.
pub fn pipeline_on<I, O, E>(
    w: usize,
    mut fill: impl FnMut(&mut Vec<I>),
    work: impl Fn(u64, &[I], &mut Vec<O>) -> Result<(), E> + Sync,
    mut consume: impl FnMut(&[O]) -> Result<(), E>,
) -> Result<(), E>
where
    I: Send,
    O: Send,
    E: Send,
{
    let w = w.max(1);
    let (mut input, mut output) = (Vec::new(), Vec::new());
    let mut first = 0u64;
    if w == 1 {
        loop {
            fill(&mut input);
            if input.is_empty() {
                return Ok(());
            }
            work(first, &input, &mut output)?;
            consume(&output)?;
            first += input.len() as u64;
        }
    }
    type Job<I, O> = (u64, Vec<I>, Vec<O>);
    type Done<I, O, E> = (Vec<I>, Vec<O>, Result<(), E>);
    std::thread::scope(|scope| {
        let work = &work;
        let (mut jobs, mut results) = (Vec::new(), Vec::new());
        for _ in 0..w {
            let (job_tx, job_rx) = std::sync::mpsc::channel::<Job<I, O>>();
            let (done_tx, done_rx) = std::sync::mpsc::channel::<Done<I, O, E>>();
            scope.spawn(move || {
                for (first, input, mut output) in job_rx {
                    let r = work(first, &input, &mut output);
                    if done_tx.send((input, output, r)).is_err() {
                        break;
                    }
                }
            });
            jobs.push(job_tx);
            results.push(done_rx);
        }
        let mut spare = vec![(input, output)];
        let (mut sent, mut received, mut filling) = (0usize, 0usize, true);
        loop {
            while filling && sent - received <= w {
                let (mut input, output) = spare.pop().unwrap_or_default();
                fill(&mut input);
                if input.is_empty() {
                    filling = false;
                    break;
                }
                let n = input.len() as u64;
                if jobs[sent % w].send((first, input, output)).is_err() {
                    // The worker is gone (it panicked): the scope re-raises its panic.
                    return Ok(());
                }
                first += n;
                sent += 1;
            }
            if received == sent {
                return Ok(());
            }
            let Ok((input, output, r)) = results[received % w].recv() else {
                return Ok(());
            };
            r?;
            consume(&output)?;
            received += 1;
            spare.push((input, output));
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_gives_each_stage_its_own_result_and_a_second_thread_where_there_are_cores() {
        let here = std::thread::current().id();
        let (a, (b, other)) = both(
            || (0..1000u64).sum::<u64>(),
            || ((1..=20u64).product::<u64>(), std::thread::current().id()),
        );
        assert_eq!((a, b), (499_500, 2_432_902_008_176_640_000));
        assert_eq!(other != here, workers() > 1);
    }

    #[test]
    fn the_pipeline_hands_every_batch_on_in_order_and_stops_at_the_first_error() {
        for n in [0usize, 1, 5, 1000, 10_007] {
            let mut next = 0usize;
            let fill = |buf: &mut Vec<usize>| {
                buf.clear();
                buf.extend(next..(next + 97).min(n));
                next = (next + 97).min(n);
            };
            let mut seen = Vec::new();
            pipeline(
                fill,
                |first, input: &[usize], out: &mut Vec<(u64, usize)>| {
                    out.clear();
                    out.extend(input.iter().map(|&i| (first, i * 3)));
                    Ok::<(), usize>(())
                },
                |out| {
                    seen.extend_from_slice(out);
                    Ok(())
                },
            )
            .unwrap();
            assert_eq!(seen.len(), n);
            for (k, (first, v)) in seen.iter().enumerate() {
                assert_eq!((*v, *first as usize), (3 * k, k - k % 97), "n {n}");
            }
        }
        let mut next = 0usize;
        let e = pipeline(
            |buf: &mut Vec<usize>| {
                buf.clear();
                buf.extend(next..(next + 10).min(1000));
                next += 10;
            },
            |_, input, out: &mut Vec<usize>| match input.iter().find(|&&i| i % 300 == 299) {
                Some(&i) => Err(i),
                None => {
                    out.clear();
                    out.extend_from_slice(input);
                    Ok(())
                }
            },
            |_| Ok(()),
        );
        assert_eq!(e, Err(299));
    }

    #[test]
    fn items_handed_out_one_at_a_time_are_each_made_once_and_the_first_error_wins() {
        // Items of very uneven cost (every 16th spins a thousand times longer): each slot gets
        // its own item, each item is made once; of three failing items the first in order is
        // the error, whichever thread met it.
        for n in [0usize, 1, 2, 3, 17, 500] {
            let made = std::sync::atomic::AtomicUsize::new(0);
            let mut out = vec![usize::MAX; n];
            fill_each(&mut out, |k| {
                made.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let spins = if k % 16 == 0 { 100_000 } else { 100 };
                let v = (0..spins).fold(k, |a, i| std::hint::black_box(a ^ i) ^ i);
                Ok::<usize, ()>(v * 2)
            })
            .unwrap();
            assert_eq!(out, (0..n).map(|k| 2 * k).collect::<Vec<_>>());
            assert_eq!(made.into_inner(), n);
        }
        let mut out = vec![0; 200];
        let e = fill_each(&mut out, |k| match k {
            90 | 17 | 40 => Err(k),
            _ => Ok(k),
        });
        assert_eq!(e, Err(17));
    }

    #[test]
    fn a_record_read_ahead_is_its_fill_in_any_request_sizes_on_a_second_thread() {
        let n = 10_007;
        let here = std::thread::current().id();
        let makers = std::sync::Mutex::new(std::collections::HashSet::new());
        let fill = |first: usize, out: &mut [u64]| {
            makers.lock().unwrap().insert(std::thread::current().id());
            for (i, v) in (first..).zip(out.iter_mut()) {
                *v = (i as u64).wrapping_mul(2_654_435_761) % 1_000_003;
            }
        };
        let mut direct = vec![0; n];
        fill(0, &mut direct);
        makers.lock().unwrap().clear();
        for block in [1, 7, 1000, 4096, n, 2 * n] {
            let read = read_ahead(n, block, fill, |next| {
                // Requests of changing sizes, across the blocks' ends.
                let (mut got, mut first, mut size) = (vec![0; n], 0, 1);
                while first < n {
                    let k = size.min(n - first);
                    next(first, &mut got[first..first + k]);
                    (first, size) = (first + k, size * 3 % 1021 + 1);
                }
                got
            });
            assert_eq!(read, direct, "block {block}");
        }
        let made_elsewhere = makers.lock().unwrap().iter().any(|&t| t != here);
        assert_eq!(made_elsewhere, workers() > 1);
        // A reader that stops after a few items stops the making: this returns.
        let few = read_ahead(n, 10, fill, |next| {
            let mut three = [0; 3];
            next(0, &mut three);
            three
        });
        assert_eq!(few, direct[..3]);
    }

    #[test]
    fn parts_cover_the_range_once_in_order() {
        for n in [0, 1, 2, 7, 1000] {
            let parts = map_parts(n, |r| r);
            assert!((1..=workers().max(1)).contains(&parts.len()), "n {n}");
            let items: Vec<usize> = parts.into_iter().flatten().collect();
            assert_eq!(items, (0..n).collect::<Vec<_>>(), "n {n}");
        }
    }

    #[test]
    fn chunks_cover_every_item_once_with_its_index() {
        for n in [0usize, 1, 2, 3, 17, 1000] {
            let mut out = vec![usize::MAX; n];
            fill_chunks(&mut out, |first, part| {
                for (j, slot) in part.iter_mut().enumerate() {
                    *slot = first + j;
                }
                Ok::<(), ()>(())
            })
            .unwrap();
            assert!(out.iter().enumerate().all(|(i, &v)| v == i), "n = {n}");
        }
    }

    #[test]
    fn mapped_indices_are_each_value_in_order() {
        for n in [0usize, 1, 2, 3, 17, 1000] {
            let value = |i: usize| (i * i) as f64 - 0.5;
            let expected: Vec<f64> = (0..n).map(value).collect();
            assert_eq!(map_indices(n, value), expected, "n = {n}");
        }
    }

    #[test]
    fn the_first_error_in_order_wins() {
        let mut out = vec![0u8; 1000];
        let e = fill_chunks(&mut out, |first, part| {
            (0..part.len())
                .find(|j| (first + j) % 300 == 299)
                .map_or(Ok(()), |j| Err(first + j))
        });
        assert_eq!(e, Err(299));
    }
}
