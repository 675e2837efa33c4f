//! Minimal CSV writer for the point-test tables (one header line, numbers in shortest
//! round-trip form).

use std::fmt::Write as _;
use std::path::Path;

/// Writes `header` and `rows` to `path` as comma-separated values.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<f64>]) -> std::io::Result<()> {
    let mut text = String::with_capacity(32 * header.len() * (rows.len() + 1));
    text.push_str(&header.join(","));
    text.push('\n');
    for row in rows {
        for (i, v) in row.iter().enumerate() {
            if i > 0 {
                text.push(',');
            }
            // Writing into a String cannot fail.
            let _ = write!(text, "{v}");
        }
        text.push('\n');
    }
    std::fs::write(path, text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_numbers() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.csv");
        write_csv(&path, &["a", "b"], &[vec![0.1, -2.5e-9], vec![1e300, 3.0]]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "a,b");
        let back: Vec<f64> = lines[1].split(',').map(|s| s.parse().unwrap()).collect();
        assert_eq!(back, vec![0.1, -2.5e-9]);
        assert_eq!(lines.len(), 3);
    }
}
