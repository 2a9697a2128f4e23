//! The threads a run works on (`--threads N`): the scene is read on them
//! (`src/scene/parallel.rs`), then a render's pool, started before anything is built,
//! builds the hierarchy (`src/render/bvh.rs`) and the camera rays' tiles
//! (`src/render/tiles.rs`) as well as tracing the pixels. Every value is computed as on
//! one thread, only the order of the work differs: the scene and the image are the same
//! for every N.
//!
//! Without the `threads` feature (the WebAssembly build) everything runs on the calling
//! thread.

use crate::render::Options;

/// The most worker threads a run starts, whatever [`Options::threads`] asks for: beyond
/// the cores there is nothing to gain, and a typo must not start 100,000 threads.
pub const MAX_THREADS: usize = 256;

/// The items a thread takes at a time in [`Threads::fold_slices`]: enough that handing
/// them over costs little beside their work.
#[cfg_attr(not(feature = "threads"), allow(dead_code))]
const FOLD_SLICE: usize = 1 << 15;

/// A pool of worker threads, or none: the calling thread does the work.
pub(crate) struct Threads {
    #[cfg(feature = "threads")]
    pool: Option<rayon::ThreadPool>,
}

impl Threads {
    /// The calling thread alone.
    pub(crate) fn one() -> Threads {
        Threads {
            #[cfg(feature = "threads")]
            pool: None,
        }
    }

    /// The threads `options` asks for: a pool of `options.threads` (0: one per core, at
    /// most [`MAX_THREADS`]) unless that is 1, or the pool cannot be started.
    pub(crate) fn of(options: &Options) -> Threads {
        Threads::new(options.threads)
    }

    /// A pool of `count` threads (0: one per core, at most [`MAX_THREADS`]) unless that
    /// is 1, or the pool cannot be started.
    pub(crate) fn new(count: usize) -> Threads {
        #[cfg(feature = "threads")]
        if count != 1 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(count.min(MAX_THREADS))
                .build()
                .ok();
            return Threads { pool };
        }
        let _ = count;
        Threads::one()
    }

    /// The pool, if there is one.
    #[cfg(feature = "threads")]
    pub(crate) fn pool(&self) -> Option<&rayon::ThreadPool> {
        self.pool.as_ref()
    }

    /// How many threads share the work.
    pub(crate) fn count(&self) -> usize {
        #[cfg(feature = "threads")]
        if let Some(pool) = &self.pool {
            return pool.current_num_threads();
        }
        1
    }

    /// `f()` on one of the threads: where [`Threads::join`] is called from inside `f`, it
    /// spreads the work over them.
    pub(crate) fn run<T: Send>(&self, f: impl FnOnce() -> T + Send) -> T {
        #[cfg(feature = "threads")]
        if let Some(pool) = &self.pool {
            return pool.install(f);
        }
        f()
    }

    /// `a()` and `b()`, at once on two threads where called inside [`Threads::run`] on a
    /// pool, else one after the other.
    pub(crate) fn join<A: Send, B: Send>(
        &self,
        a: impl FnOnce() -> A + Send,
        b: impl FnOnce() -> B + Send,
    ) -> (A, B) {
        #[cfg(feature = "threads")]
        if self.pool.is_some() {
            return rayon::join(a, b);
        }
        (a(), b())
    }

    /// Whether [`Threads::fold_slices`] spreads `n` items over the threads: where there
    /// are [`FOLD_SLICE`] items or more to a thread and a pool.
    pub(crate) fn slices(&self, n: usize) -> bool {
        #[cfg(feature = "threads")]
        if self.pool.is_some() {
            return n >= 2 * FOLD_SLICE;
        }
        let _ = n;
        false
    }

    /// `f` over slices of `items` on the threads, called inside [`Threads::run`], the
    /// results combined in order by `combine`: `f(items)` wherever `combine` is exact
    /// and associative (unions of boxes, sums of counts).
    pub(crate) fn fold_slices<I: Send, T: Send>(
        &self,
        items: &mut [I],
        f: impl Fn(&mut [I]) -> T + Sync + Send,
        combine: impl Fn(T, T) -> T + Sync + Send,
    ) -> T {
        #[cfg(feature = "threads")]
        if self.pool.is_some() {
            use rayon::prelude::*;
            return (items.par_chunks_mut(FOLD_SLICE).map(f))
                .reduce_with(combine)
                .expect("at least one slice");
        }
        let _ = &combine;
        f(items)
    }

    /// `items` appended to `to`, moved on the threads (called outside [`Threads::run`]).
    pub(crate) fn append<T: Send>(&self, to: &mut Vec<T>, items: Vec<T>) {
        #[cfg(feature = "threads")]
        if let Some(pool) = &self.pool {
            use rayon::prelude::*;
            return pool.install(|| to.par_extend(items));
        }
        to.extend(items);
    }

    /// `f(i)` for every i in `0..n`, in order, spread over the threads.
    pub(crate) fn map<T: Send>(&self, n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
        #[cfg(feature = "threads")]
        if let Some(pool) = &self.pool {
            use rayon::prelude::*;
            return pool.install(|| (0..n).into_par_iter().map(f).collect());
        }
        (0..n).map(f).collect()
    }
}
