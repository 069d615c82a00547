//! The viewer's truth: the report's ray-traced truth (`src/reference`: the sky with exact
//! visibility, the point lights, one bounce, normal maps and cut-outs) of the view on screen,
//! traced progressively on a thread of its own with a pool that takes only what the window leaves
//! (the system's idle class on every core; where there is none, the cores less one).
//!
//! A trace is two independent traces added up in rounds, each round doubling the rays a pixel
//! of both (1, 2, 4, ...), so after every round the truth is the report's mean of two traces of
//! N rays, with the report's noise floor (the half difference of the two). A new view (camera,
//! scene, sky, lights, sky scale, ambient or size) stops the running round at its next row and
//! starts anew; the frame loop never waits on the trace, and without the truth view the thread
//! does not exist.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use crate::reference::{self, Reference, ReferenceScene, TraceSettings};
use crate::scene::{LightRig, Model, OrbitCamera, PointLight, Skybox};

/// The most rays a pixel one of the two traces adds up to (the truth then holds twice as many).
pub const MAX_RAYS_PER_TRACE: u32 = 4096;

/// What the truth's memory costs a traced pixel at most: the two traces, the round's two, their
/// sums, and the mean the viewer measures with (eight images of about 110 bytes a pixel).
pub const BYTES_PER_PIXEL: u64 = 1024;

/// What decides the truth of a view: a change of any of these starts the trace anew.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewKey {
    pub camera: OrbitCamera,
    /// Bumped whenever the model, the sky or the lights change.
    pub scene: u64,
    /// The truth's size (the view's, or a fraction of it).
    pub size: (u32, u32),
    pub sky_scale: f32,
    pub ambient: f32,
    pub radius: f32,
}

/// One view to trace, with everything the trace reads.
pub struct Job {
    pub key: ViewKey,
    /// The model (its BVH is built on the trace's thread, once a model) and its scene number.
    pub model: Arc<Model>,
    pub sky: Arc<Skybox>,
    pub lights: Vec<PointLight>,
    pub rig: LightRig,
    /// The G-buffer's reverse-Z depth at the truth's size, row by row.
    pub depth: Vec<f32>,
    pub seed: u64,
}

/// The truth so far: two independent traces of as many rays a pixel each.
pub struct Rounds {
    pub key: ViewKey,
    pub a: Arc<Reference>,
    pub b: Arc<Reference>,
    pub rays_per_trace: u32,
    /// How long the last round took (it doubled the rays): the next takes about twice as long.
    pub last_round: Duration,
    /// Since the view's trace began.
    pub elapsed: Duration,
}

impl Rounds {
    /// Rays a pixel in the truth (both traces).
    pub fn rays(&self) -> u32 {
        2 * self.rays_per_trace
    }

    /// About how long until the rays double again (`None`: the trace is complete).
    pub fn next_doubling(&self) -> Option<Duration> {
        (self.rays_per_trace < MAX_RAYS_PER_TRACE).then(|| 2 * self.last_round)
    }
}

/// The thread that traces, and what it has traced.
pub struct Tracer {
    jobs: mpsc::Sender<Job>,
    /// The job the thread should be tracing; a round whose job is older stops at its next row.
    generation: Arc<AtomicU64>,
    latest: Arc<Mutex<Option<Arc<Rounds>>>>,
    /// The traces' worker threads: every core in the idle class, else the cores less one.
    pub threads: usize,
}

impl Tracer {
    /// Starts the thread (and its pool); it waits for a job.
    pub fn start() -> std::io::Result<Self> {
        let (jobs, received) = mpsc::channel();
        let generation = Arc::new(AtomicU64::new(0));
        let latest = Arc::new(Mutex::new(None));
        let (g, l) = (generation.clone(), latest.clone());
        let (told, threads) = mpsc::sync_channel(1);
        std::thread::Builder::new().name("ssdo-truth".into()).spawn(move || {
            // The window's threads first: where the system has an idle class (Linux), the
            // trace's threads run in it on every core, and take only what the window leaves
            // (measured: no frame of the bench slower with two such threads tracing); elsewhere
            // one core fewer than the machine has is the trace's.
            let idle = run_when_idle();
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            let threads = if idle { cores } else { cores.saturating_sub(1).max(1) };
            let _ = told.send(threads);
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .thread_name(|i| format!("ssdo-truth-{i}"))
                .start_handler(move |_| {
                    if idle {
                        run_when_idle();
                    }
                })
                .build();
            if let Ok(pool) = pool {
                work(&received, &g, &l, &pool);
            }
        })?;
        let threads = threads.recv().map_err(std::io::Error::other)?;
        Ok(Self { jobs, generation, latest, threads })
    }

    /// Traces `job`'s view from nothing, stopping what was traced before.
    pub fn trace(&self, job: Job) {
        self.stop();
        if let Ok(mut latest) = self.latest.lock() {
            *latest = None;
        }
        // The thread is gone only if it panicked: the truth then stays as it was.
        let _ = self.jobs.send(job);
    }

    /// Stops the running trace at its next row; nothing more is traced until the next job.
    pub fn stop(&self) {
        self.generation.fetch_add(1, Ordering::SeqCst);
    }

    /// The newest rounds of the view being traced.
    pub fn latest(&self) -> Option<Arc<Rounds>> {
        self.latest.lock().ok().and_then(|l| l.clone())
    }
}

impl Drop for Tracer {
    fn drop(&mut self) {
        // The round stops at its next row; the thread ends when it finds the channel closed.
        self.stop();
    }
}

/// Puts the calling thread in the system's idle scheduling class, where it runs only when no
/// other thread wants the core (Linux's `SCHED_IDLE`); whether it could.
fn run_when_idle() -> bool {
    #[cfg(target_os = "linux")]
    {
        let param = libc::sched_param { sched_priority: 0 };
        // SAFETY: pid 0 is the calling thread; the parameter is a valid, initialised struct.
        unsafe { libc::sched_setscheduler(0, libc::SCHED_IDLE, &param) == 0 }
    }
    #[cfg(not(target_os = "linux"))]
    {
        false
    }
}

/// The thread's loop: the newest job, traced round after round on `pool` until it is done or
/// replaced.
fn work(
    jobs: &mpsc::Receiver<Job>,
    generation: &AtomicU64,
    latest: &Mutex<Option<Arc<Rounds>>>,
    pool: &rayon::ThreadPool,
) {
    let mut built: Option<(Arc<Model>, Arc<ReferenceScene>)> = None;
    while let Ok(mut job) = jobs.recv() {
        // Only the newest job counts; the others' views are gone.
        while let Ok(newer) = jobs.try_recv() {
            job = newer;
        }
        let wanted = generation.load(Ordering::SeqCst);
        let scene = match &built {
            Some((model, scene)) if Arc::ptr_eq(model, &job.model) => scene.clone(),
            _ => {
                let scene = Arc::new(pool.install(|| ReferenceScene::new(&job.model)));
                built = Some((job.model.clone(), scene.clone()));
                scene
            }
        };
        let go_on = || generation.load(Ordering::Relaxed) == wanted;
        trace_rounds(pool, &scene, &job, &go_on, &|rounds| {
            if go_on() {
                if let Ok(mut l) = latest.lock() {
                    *l = Some(Arc::new(rounds));
                }
            }
        });
    }
}

/// Traces `job` in rounds until each trace holds `rays_per_trace` rays a pixel (or the most
/// there are), on `pool`: the rounds the viewer shows, at once (for tests and tools).
pub fn trace_to(pool: &rayon::ThreadPool, job: &Job, rays_per_trace: u32) -> Option<Rounds> {
    let scene = pool.install(|| ReferenceScene::new(&job.model));
    let last = Mutex::new(None);
    let short = |l: &Option<Rounds>| l.as_ref().is_none_or(|r| r.rays_per_trace < rays_per_trace);
    let go_on = || last.lock().is_ok_and(|l| short(&l));
    trace_rounds(pool, &scene, job, &go_on, &|rounds| {
        if let Ok(mut l) = last.lock() {
            *l = Some(rounds);
        }
    });
    last.into_inner().ok().flatten()
}

/// The two independent traces of a view.
type TwoTraces = (Arc<Reference>, Arc<Reference>);

/// Traces `job` in rounds that double its rays, telling `publish` each round's sum, until the
/// rays reach [`MAX_RAYS_PER_TRACE`] or `go_on` says stop.
fn trace_rounds(
    pool: &rayon::ThreadPool,
    scene: &ReferenceScene,
    job: &Job,
    go_on: &(dyn Fn() -> bool + Sync),
    publish: &dyn Fn(Rounds),
) {
    let started = Instant::now();
    // The two traces' sums so far, and the rays a pixel each holds.
    let mut sums: Option<TwoTraces> = None;
    let mut rays = 0u32;
    for round in 0u64.. {
        let add = rays.max(1);
        if rays + add > MAX_RAYS_PER_TRACE || !go_on() {
            return;
        }
        let round_started = Instant::now();
        let trace = |which: u64| {
            let settings = TraceSettings {
                samples_per_pixel: add,
                // Every round and trace its own stream of rays (the report's two seeds, mixed).
                seed: job.seed ^ 0x5DEE_CE66_D1CE_4E5B_u64.wrapping_mul(2 * round + which + 1),
                radius: job.key.radius,
                sky_scale: job.key.sky_scale,
                ambient: job.key.ambient,
            };
            let lit = (job.lights.as_slice(), &job.rig);
            let view = (job.key.size, job.depth.as_slice());
            pool.install(|| reference::trace_while(scene, lit, &job.sky, &job.key.camera, view, &settings, go_on))
        };
        let (Some(a), Some(b)) = (trace(0), trace(1)) else { return };
        let added = |old: &Option<Arc<Reference>>, new: Reference| match old {
            None => Arc::new(new),
            Some(old) => Arc::new(Reference::weighted_mean((old, rays as f64), (&new, add as f64))),
        };
        let (a, b) = (added(&sums.as_ref().map(|s| s.0.clone()), a), added(&sums.as_ref().map(|s| s.1.clone()), b));
        rays += add;
        sums = Some((a.clone(), b.clone()));
        publish(Rounds {
            key: job.key,
            a,
            b,
            rays_per_trace: rays,
            last_round: round_started.elapsed(),
            elapsed: started.elapsed(),
        });
    }
}

/// The depth of `size` (the truth's) taken from the G-buffer's `depth` of `full` size: each
/// truth pixel reads the G-buffer pixel under its centre.
pub fn depth_at(depth: &[f32], full: (u32, u32), size: (u32, u32)) -> Vec<f32> {
    if full == size {
        return depth.to_vec();
    }
    let mut out = Vec::with_capacity((size.0 * size.1) as usize);
    for y in 0..size.1 {
        let fy = (((y as f64 + 0.5) * full.1 as f64 / size.1 as f64) as u32).min(full.1 - 1);
        for x in 0..size.0 {
            let fx = (((x as f64 + 0.5) * full.0 as f64 / size.0 as f64) as u32).min(full.0 - 1);
            out.push(depth[(fy * full.0 + fx) as usize]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fraction_of_the_view_reads_the_depth_under_each_pixels_centre() {
        let depth: Vec<f32> = (0..16).map(|i| i as f32).collect();
        assert_eq!(depth_at(&depth, (4, 4), (4, 4)), depth);
        // 2x2 of 4x4: centres at 1 and 3 of each axis.
        assert_eq!(depth_at(&depth, (4, 4), (2, 2)), vec![5.0, 7.0, 13.0, 15.0]);
        assert_eq!(depth_at(&depth, (4, 4), (1, 1)), vec![10.0]);
    }
}
