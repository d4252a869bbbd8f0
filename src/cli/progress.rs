//! Stage progress on stderr while `flexbody build` runs, and progress inside the long solver
//! phases (factorization, block solves, eigen iteration: [`crate::solve::progress`]).

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::solve::progress::{self, Event};

/// How often a log (stderr not a terminal) gets a line about a long phase: 5 s, or the seconds
/// in `FLEXBODY_PROGRESS_SECONDS` (0: every solver step).
fn log_every() -> Duration {
    std::env::var("FLEXBODY_PROGRESS_SECONDS")
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s >= 0.0)
        .map_or(Duration::from_secs(5), Duration::from_secs_f64)
}

/// Stage progress on stderr: on a terminal a spinner shows the running stage, its elapsed time
/// and what the solver is doing (the factorization's size, the eigenpairs converged of those
/// wanted with an estimate of the time left); every finished stage leaves one line with its
/// duration. When stderr is a log, a long phase prints a line every few seconds instead.
pub(crate) struct StageProgress {
    quiet: bool,
    bar: Option<indicatif::ProgressBar>,
    current: Option<(String, Instant)>,
    live: Arc<Mutex<Live>>,
}

/// What the solver last reported, shared with the reporter the solve layer calls.
#[derive(Default)]
struct Live {
    stage: String,
    /// The eigen iteration's start, for the estimate.
    eigen_start: Option<Instant>,
    /// The stage's start or the last line written to a log.
    last_log: Option<Instant>,
    /// [`log_every`].
    every: Duration,
    /// The running factorization's description ("factorizing K (…)"), for its share lines.
    factor: String,
}

impl StageProgress {
    pub(crate) fn new(quiet: bool) -> StageProgress {
        let bar = (!quiet).then(|| {
            let bar = indicatif::ProgressBar::new_spinner();
            if let Ok(style) =
                indicatif::ProgressStyle::with_template("flexbody: {spinner} {msg} {elapsed}")
            {
                bar.set_style(style);
            }
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        });
        let live = Arc::new(Mutex::new(Live::default()));
        if let Some(bar) = &bar {
            let (bar, live) = (bar.clone(), live.clone());
            progress::set_reporter(Some(Arc::new(move |e: &Event| {
                // a poisoned lock only means an earlier report panicked; the state is plain data
                let mut l = live.lock().unwrap_or_else(|p| p.into_inner());
                show(&bar, &mut l, e);
            })));
        }
        StageProgress {
            quiet,
            bar,
            current: None,
            live,
        }
    }

    pub(crate) fn stage(&mut self, name: &str) {
        super::alloc_guard::set_stage(name);
        self.end_current();
        self.current = Some((name.to_string(), Instant::now()));
        let mut l = self.live.lock().unwrap_or_else(|p| p.into_inner());
        // a log hears of a phase only once the stage has run `every` (short builds stay quiet)
        *l = Live {
            stage: name.to_string(),
            eigen_start: None,
            last_log: Some(Instant::now()),
            every: log_every(),
            factor: String::new(),
        };
        if let Some(bar) = &self.bar {
            bar.set_message(format!("{name:<14}"));
        }
    }

    fn end_current(&mut self) {
        let Some((name, t)) = self.current.take() else {
            return;
        };
        if self.quiet {
            return;
        }
        let line = format!("flexbody: {name:<14} {:8.2} s", t.elapsed().as_secs_f64());
        match &self.bar {
            Some(bar) if !bar.is_hidden() => bar.println(line),
            _ => eprintln!("{line}"),
        }
    }

    pub(crate) fn finish(&mut self) {
        self.end_current();
        progress::set_reporter(None);
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

/// The solver's step as a message: on the spinner, or as a line in a log at most every
/// [`log_every`].
fn show(bar: &indicatif::ProgressBar, l: &mut Live, e: &Event) {
    let what = match *e {
        Event::FactorStart { n, flops, single } => {
            l.factor = format!(
                "factorizing K ({n} equations, {:.1} GFlop{})",
                flops / 1e9,
                if single { ", f32" } else { "" }
            );
            l.factor.clone()
        }
        Event::FactorProgress { share } => format!("{}: {:.0} % done", l.factor, 100.0 * share),
        Event::FactorEnd => "factorized".into(),
        Event::Solves { columns } => format!("solving for {columns} right-hand sides"),
        Event::Eigen { converged, wanted } => {
            let start = *l.eigen_start.get_or_insert_with(Instant::now);
            format!(
                "eigen {converged}/{wanted} converged{}",
                time_left(start, converged, wanted)
            )
        }
    };
    let message = format!("{:<14} {what}", l.stage);
    if !bar.is_hidden() {
        bar.set_message(message);
        return;
    }
    let now = Instant::now();
    if l.last_log.is_none_or(|t| now.duration_since(t) >= l.every) {
        l.last_log = Some(now);
        eprintln!("flexbody:   {message}");
    }
}

/// ", ~N s left" from the rate so far (linear in converged pairs), once there is a rate.
fn time_left(start: Instant, converged: usize, wanted: usize) -> String {
    let elapsed = start.elapsed().as_secs_f64();
    if converged == 0 || converged >= wanted || elapsed < 0.5 {
        return String::new();
    }
    let left = elapsed / converged as f64 * (wanted - converged) as f64;
    format!(", ~{left:.0} s left")
}
