//! Work split over the machine's cores: every core natively, one thread in the browser, where
//! the module has no threads and spawning one would trap. Each item is computed alone, so a
//! result never depends on how the work was split.

/// Threads for parallel work: every core natively, one in the browser.
pub fn workers() -> usize {
    if cfg!(target_arch = "wasm32") {
        return 1;
    }
    // Asked once: the standard library reads the cgroup's quota files each time.
    static WORKERS: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *WORKERS.get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
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

#[cfg(test)]
mod tests {
    use super::*;

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
