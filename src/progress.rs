//! Progress on stderr: indicatif bars when stderr is a terminal, otherwise plain
//! lines at most once per second per task, so logs stay readable in CI.

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::collections::HashMap;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

pub struct Progress {
    quiet: bool,
    tty: bool,
    multi: MultiProgress,
    bars: Mutex<HashMap<String, ProgressBar>>,
    /// Plain mode: when each task last printed; terminal mode: when it started.
    last_line: Mutex<HashMap<String, Instant>>,
}

impl Progress {
    pub fn new(quiet: bool) -> Progress {
        Progress {
            quiet,
            tty: std::io::stderr().is_terminal(),
            multi: MultiProgress::new(),
            bars: Mutex::new(HashMap::new()),
            last_line: Mutex::new(HashMap::new()),
        }
    }

    /// Reports `done` of `total` units of `what` in `stage` (total 0: unknown).
    pub fn report(&self, stage: &str, what: &str, done: u64, total: u64) {
        if self.quiet {
            return;
        }
        let key = format!("{stage}: {what}");
        if self.tty {
            let mut bars = self.bars.lock().unwrap_or_else(|e| e.into_inner());
            // Only tasks lasting over a second get a bar.
            if !bars.contains_key(&key) {
                let mut seen = self.last_line.lock().unwrap_or_else(|e| e.into_inner());
                let first = *seen.entry(key.clone()).or_insert_with(Instant::now);
                if first.elapsed() < Duration::from_secs(1) || (total > 0 && done >= total) {
                    return;
                }
            }
            let bar = bars.entry(key.clone()).or_insert_with(|| {
                let b = self.multi.add(if total > 0 { ProgressBar::new(total) } else { ProgressBar::new_spinner() });
                b.set_style(
                    ProgressStyle::with_template("{prefix:>10} {wide_msg} [{bar:30}] {percent:>3}%")
                        .unwrap_or_else(|_| ProgressStyle::default_bar())
                        .progress_chars("=> "),
                );
                b.set_prefix(stage.to_string());
                b.set_message(what.to_string());
                b
            });
            if total > 0 {
                bar.set_length(total);
            }
            bar.set_position(done.min(total.max(done)));
            if total > 0 && done >= total {
                bar.finish_and_clear();
                bars.remove(&key);
            }
        } else {
            let mut last = self.last_line.lock().unwrap_or_else(|e| e.into_inner());
            let now = Instant::now();
            let finished = total > 0 && done >= total;
            let due = last.get(&key).is_none_or(|t| now.duration_since(*t) >= Duration::from_secs(1));
            if due && !finished && done > 0 {
                if total > 0 {
                    eprintln!("{key} {:.0}%", 100.0 * done as f64 / total as f64);
                } else {
                    eprintln!("{key} {done}");
                }
                last.insert(key, now);
            }
        }
    }

    /// Whether progress output is off (`-q`); errors are still printed.
    pub fn is_quiet(&self) -> bool {
        self.quiet
    }

    /// A line of stage output (not a progress update).
    pub fn line(&self, text: &str) {
        if self.quiet {
            return;
        }
        let text = for_terminal(text);
        if self.tty {
            let _ = self.multi.println(text);
        } else {
            eprintln!("{text}");
        }
    }
}

/// The most characters of one line [`for_terminal`] prints: an error can
/// quote a file's words whole (serde quotes a string where a number
/// belongs), megabytes of them from a damaged file, which would bury the
/// terminal. The run's JSON (`--json`) keeps a stage's lines and errors
/// whole.
const MAX_LINE_CHARS: usize = 10_000;

/// `text` as it is safe to print: each control character but a line break
/// and a tab shown as U+FFFD, and each line longer than [`MAX_LINE_CHARS`]
/// characters cut in its middle (its start and its end kept, where an
/// error says what to do, with how many characters were left out). The lines a run prints carry
/// names and words read from files others made (a plant model's, a crane
/// rental's chart, a damaged cache entry), and a terminal takes an escape
/// or a carriage return in them as an order: a "\r" can print "validated"
/// over what a line said before it, an escape hide text or set the
/// window's title.
pub fn for_terminal(text: &str) -> std::borrow::Cow<'_, str> {
    let unsafe_char = |c: char| c.is_control() && c != '\n' && c != '\t';
    let long = |line: &str| line.chars().nth(MAX_LINE_CHARS).is_some();
    if !text.chars().any(unsafe_char) && !text.split('\n').any(long) {
        return std::borrow::Cow::Borrowed(text);
    }
    let lines: Vec<String> = text
        .split('\n')
        .map(|line| {
            let shown = |chars: &mut dyn Iterator<Item = char>| -> String {
                chars.map(|c| if unsafe_char(c) { '\u{FFFD}' } else { c }).collect()
            };
            let count = line.chars().count();
            if count <= MAX_LINE_CHARS {
                return shown(&mut line.chars());
            }
            let half = MAX_LINE_CHARS / 2;
            format!(
                "{} ... ({} characters left out) ... {}",
                shown(&mut line.chars().take(half)),
                count - 2 * half,
                shown(&mut line.chars().skip(count - half))
            )
        })
        .collect();
    std::borrow::Cow::Owned(lines.join("\n"))
}

/// Where the run's log (`tracing`'s warnings, and more with `-v`) goes:
/// stderr, each event as [`log_event`] makes it safe. The stages log the
/// names of files others made (a survey's scan file, a plant model's
/// block) as they are, and a name holding a line break printed a line of
/// its own ("error: ..."), as the run's own lines did before they were
/// printed through [`for_terminal`].
pub struct TerminalLog;

impl<'a> tracing_subscriber::fmt::MakeWriter<'a> for TerminalLog {
    type Writer = LogEvent<std::io::Stderr>;

    fn make_writer(&'a self) -> Self::Writer {
        LogEvent { text: Vec::new(), out: std::io::stderr() }
    }
}

/// One event's text, gathered and printed as [`log_event`] makes it when
/// the logger is done with it (it may write an event in pieces).
pub struct LogEvent<W: std::io::Write> {
    text: Vec<u8>,
    out: W,
}

impl<W: std::io::Write> std::io::Write for LogEvent<W> {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.text.extend_from_slice(bytes);
        Ok(bytes.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl<W: std::io::Write> Drop for LogEvent<W> {
    fn drop(&mut self) {
        if self.text.is_empty() {
            return;
        }
        let text = String::from_utf8_lossy(&self.text);
        // A log line that cannot be printed is not worth failing the run.
        let _ = writeln!(self.out, "{}", log_event(&text));
        let _ = self.out.flush();
    }
}

/// A log event's text as it is safe to print: [`for_terminal`]'s, on one
/// line's start: a line break inside it (from a name it quotes) is shown
/// as the line going on, indented, so that nothing it quotes reads as a
/// line of the run's own.
pub fn log_event(text: &str) -> String {
    for_terminal(text.strip_suffix('\n').unwrap_or(text)).replace('\n', "\n    ")
}

#[cfg(test)]
mod tests {
    use super::{LogEvent, MAX_LINE_CHARS, for_terminal, log_event};

    #[test]
    fn control_characters_are_not_printed() {
        assert_eq!(for_terminal("plan ran: 0.50 m to /FDN-V101\n\tnext"), "plan ran: 0.50 m to /FDN-V101\n\tnext");
        assert_eq!(for_terminal("NOT VALIDATED\rvalidated"), "NOT VALIDATED\u{FFFD}validated");
        assert_eq!(
            for_terminal("\x1b]0;title\x07\x1b[8mhidden\u{9b}"),
            "\u{FFFD}]0;title\u{FFFD}\u{FFFD}[8mhidden\u{FFFD}"
        );
    }

    /// A scan file's name holding a line break and an escape, logged by a
    /// stage as it is, prints on the event's line and an indented one; no
    /// escape reaches the terminal.
    #[test]
    fn a_logged_name_does_not_print_a_line_of_its_own() {
        assert_eq!(log_event("WARN scan.laz: fine\n"), "WARN scan.laz: fine");
        let mut out = Vec::new();
        {
            use std::io::Write;
            let mut event = LogEvent { text: Vec::new(), out: &mut out };
            event.write_all(b" WARN scans/scan-3\nerror: evil\x1b[2J.xyz:").unwrap();
            event.write_all(b"4: count line declares 9 points, 3 follow\n").unwrap();
        }
        let printed = String::from_utf8(out).unwrap();
        assert_eq!(
            printed,
            " WARN scans/scan-3\n    error: evil\u{FFFD}[2J.xyz:4: count line declares 9 points, 3 follow\n"
        );
        assert!(printed.lines().skip(1).all(|l| l.starts_with("    ")), "{printed}");
    }

    /// A line of megabytes (a damaged file's words quoted in an error) is
    /// cut in its middle, saying how much was left out, its end (what to
    /// do) kept; the lines around it are whole.
    #[test]
    fn a_line_too_long_to_read_is_cut() {
        let fits = "é".repeat(MAX_LINE_CHARS);
        assert_eq!(for_terminal(&fits), fits);
        let said = format!("error: invalid type: string \"{}\", expected f64; rerun", "x".repeat(2_000_000));
        let printed = for_terminal(&format!("first\n{said}\nlast")).into_owned();
        let lines: Vec<&str> = printed.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!((lines[0], lines[2]), ("first", "last"));
        let (half, left_out) = (MAX_LINE_CHARS / 2, said.len() - MAX_LINE_CHARS);
        let (start, end) = (&said[..half], &said[said.len() - half..]);
        assert_eq!(lines[1], format!("{start} ... ({left_out} characters left out) ... {end}"));
        assert!(lines[1].ends_with("\", expected f64; rerun"), "{}", &lines[1][lines[1].len() - 80..]);
    }
}
