//! Problems found in a scene file, each located by file, line, column and key path.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::de::{DeTable, DeValue};

/// How bad a problem is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// The run proceeds, but the user should know.
    Warning,
    /// The run is refused.
    Error,
}

/// One segment of a key path: a table key or an array index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum KeySegment {
    /// `table.key`.
    Key(String),
    /// `array[index]`.
    Index(usize),
}

/// A key path such as `particles[0].radius_m`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct KeyPath(pub Vec<KeySegment>);

impl KeyPath {
    /// The root.
    pub fn root() -> Self {
        Self(Vec::new())
    }

    /// This path followed by `key`.
    pub fn key(&self, key: &str) -> Self {
        let mut p = self.clone();
        p.0.push(KeySegment::Key(key.to_owned()));
        p
    }

    /// This path followed by `[index]`.
    pub fn index(&self, index: usize) -> Self {
        let mut p = self.clone();
        p.0.push(KeySegment::Index(index));
        p
    }
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut first = true;
        for s in &self.0 {
            match s {
                KeySegment::Key(k) => {
                    if !first {
                        f.write_str(".")?;
                    }
                    f.write_str(k)?;
                }
                KeySegment::Index(i) => write!(f, "[{i}]")?,
            }
            first = false;
        }
        Ok(())
    }
}

/// One problem of a scene file.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// Error or warning.
    pub severity: Severity,
    /// Scene file.
    pub file: PathBuf,
    /// 1-based line (0 when unknown).
    pub line: usize,
    /// 1-based column (0 when unknown).
    pub column: usize,
    /// Key path (empty for whole-file problems).
    pub key: String,
    /// What is wrong, with the allowed range.
    pub message: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(f, "{}", self.file.display())?;
        if self.line > 0 {
            write!(f, ":{}:{}", self.line, self.column)?;
        }
        write!(f, ": {kind}")?;
        if !self.key.is_empty() {
            write!(f, ": `{}`", self.key)?;
        }
        write!(f, ": {}", self.message)
    }
}

/// Every problem of a scene file, errors first.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Problems(pub Vec<Problem>);

impl Problems {
    /// Whether any problem is an error.
    pub fn has_errors(&self) -> bool {
        self.0.iter().any(|p| p.severity == Severity::Error)
    }

    /// The errors.
    pub fn errors(&self) -> impl Iterator<Item = &Problem> {
        self.0.iter().filter(|p| p.severity == Severity::Error)
    }

    /// The warnings.
    pub fn warnings(&self) -> impl Iterator<Item = &Problem> {
        self.0.iter().filter(|p| p.severity == Severity::Warning)
    }
}

impl fmt::Display for Problems {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.errors().count();
        writeln!(f, "the scene file has {n} error(s):")?;
        for p in &self.0 {
            writeln!(f, "  {p}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Problems {}

/// Turns key paths and byte spans into file positions.
pub(crate) struct Locator<'a> {
    file: &'a Path,
    text: &'a str,
    table: Option<toml::Spanned<DeTable<'a>>>,
}

impl<'a> Locator<'a> {
    pub(crate) fn new(file: &'a Path, text: &'a str) -> Self {
        Self {
            file,
            text,
            table: DeTable::parse(text).ok(),
        }
    }

    /// 1-based line and column of byte `offset`.
    pub(crate) fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
        (line, col)
    }

    /// Span of the value at `path` (or of the deepest existing ancestor).
    pub(crate) fn span(&self, path: &KeyPath) -> Option<Range<usize>> {
        let root = self.table.as_ref()?;
        let mut span = root.span();
        let mut current: Option<&DeValue<'a>> = None;
        let mut table: Option<&DeTable<'a>> = Some(root.get_ref());
        for seg in &path.0 {
            let next = match seg {
                KeySegment::Key(k) => match (table, current) {
                    (Some(t), _) => t.get(k.as_str()),
                    (None, Some(v)) => v.get(k.as_str()),
                    _ => None,
                },
                KeySegment::Index(i) => current.and_then(|v| v.get(*i)),
            };
            let Some(next) = next else { break };
            span = next.span();
            current = Some(next.get_ref());
            table = None;
        }
        Some(span)
    }

    pub(crate) fn problem(
        &self,
        severity: Severity,
        path: &KeyPath,
        message: impl Into<String>,
    ) -> Problem {
        let (line, column) = self.span(path).map_or((0, 0), |s| self.line_col(s.start));
        Problem {
            severity,
            file: self.file.to_path_buf(),
            line,
            column,
            key: path.to_string(),
            message: message.into(),
        }
    }

    pub(crate) fn at_span(
        &self,
        severity: Severity,
        span: Option<Range<usize>>,
        key: String,
        message: String,
    ) -> Problem {
        let (line, column) = span.map_or((0, 0), |s| self.line_col(s.start));
        Problem {
            severity,
            file: self.file.to_path_buf(),
            line,
            column,
            key,
            message,
        }
    }
}
