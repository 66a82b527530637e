//! Work shared among scoped threads, or done on the calling thread where there is one
//! worker (and on targets without threads, such as `wasm32-unknown-unknown`, where
//! [`std::thread::available_parallelism`] fails and a spawn would panic).

/// `work(k)` for every `k` in `0..count`, in `k` order: on `count` scoped threads when
/// `threads > 1`, else one after another on the calling thread.
pub(crate) fn map<T: Send>(
    count: usize,
    threads: usize,
    work: impl Fn(usize) -> T + Sync,
) -> Vec<T> {
    if threads <= 1 || count <= 1 {
        return (0..count).map(work).collect();
    }
    let work = &work;
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..count).map(|k| scope.spawn(move || work(k))).collect();
        handles
            .into_iter()
            .map(|h| match h.join() {
                Ok(result) => result,
                Err(panic) => std::panic::resume_unwind(panic),
            })
            .collect()
    })
}

/// How many threads `requested` means: itself, or for 0 the machine's parallelism (1 where
/// it cannot be read).
pub(crate) fn threads(requested: usize) -> usize {
    match requested {
        0 => std::thread::available_parallelism().map_or(1, std::num::NonZero::get),
        n => n,
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn results_come_in_order_on_one_thread_and_on_several() {
        let squares: Vec<usize> = (0..9).map(|k| k * k).collect();
        assert_eq!(super::map(9, 1, |k| k * k), squares);
        assert_eq!(super::map(9, 4, |k| k * k), squares);
    }
}
