//! Stage progress on stderr while `flexbody build` runs.

/// Stage progress on stderr: on a terminal a spinner shows the running stage and its elapsed
/// time; every finished stage leaves one line with its duration (also when stderr is a log).
pub(crate) struct StageProgress {
    quiet: bool,
    bar: Option<indicatif::ProgressBar>,
    current: Option<(String, std::time::Instant)>,
}

impl StageProgress {
    pub(crate) fn new(quiet: bool) -> StageProgress {
        let bar = (!quiet).then(|| {
            let bar = indicatif::ProgressBar::new_spinner();
            if let Ok(style) =
                indicatif::ProgressStyle::with_template("flexbody: {spinner} {msg:<14} {elapsed}")
            {
                bar.set_style(style);
            }
            bar.enable_steady_tick(std::time::Duration::from_millis(120));
            bar
        });
        StageProgress {
            quiet,
            bar,
            current: None,
        }
    }

    pub(crate) fn stage(&mut self, name: &str) {
        self.end_current();
        self.current = Some((name.to_string(), std::time::Instant::now()));
        if let Some(bar) = &self.bar {
            bar.set_message(name.to_string());
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
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
