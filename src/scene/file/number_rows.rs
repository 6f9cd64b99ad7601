//! Files of rows of numbers beside a scene file (spectra, placements): numbers separated by
//! commas, semicolons, tabs or spaces; `#` comments, blank lines and a header line of words
//! before the first row skipped.

use std::path::Path;

/// The rows of numbers of the file `path` (`what` names the file's role in messages), each
/// with its line number (from 1); a line that is not all numbers is an error naming the file
/// and line, `expected` saying what the line should hold.
pub(super) fn read_number_rows(
    path: &Path,
    what: &str,
    expected: &str,
) -> Result<Vec<(usize, Vec<f64>)>, String> {
    let shown = path.display();
    let text =
        std::fs::read_to_string(path).map_err(|e| format!("cannot read {what} {shown}: {e}"))?;
    let mut rows = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        if fields.is_empty() {
            continue;
        }
        match fields.iter().map(|f| f.parse().ok()).collect() {
            Some(numbers) => rows.push((n + 1, numbers)),
            // A header of words before the first row.
            None if rows.is_empty() && fields[0].parse::<f64>().is_err() => {}
            None => return Err(format!("{shown}:{}: expected {expected}", n + 1)),
        }
    }
    Ok(rows)
}
