//! A line-by-line check of an OBJ file's vertex and face statements before `tobj` reads it,
//! so that a malformed file is refused with the line at fault (`tobj` reports no line), and
//! the line of every face, so that faces refused later can be named by their line.

/// What the check learned: the line (from 1) of every face statement, in file order (the
/// order in which `tobj` hands the faces on).
#[derive(Debug)]
pub(super) struct FaceLines(pub Vec<usize>);

impl FaceLines {
    /// The line of face `face` (counted over the whole file from 0), or 0 when unknown.
    pub fn line(&self, face: usize) -> usize {
        self.0.get(face).copied().unwrap_or(0)
    }
}

/// Checks the `v`, `vt`, `vn` and `f` statements of `text`: numbers that parse and are
/// finite, faces of at least three corners whose indices name existing data. Other
/// statements are left to `tobj`. The error is `line N: what is wrong`.
pub(super) fn check(text: &str) -> Result<FaceLines, String> {
    let statements = || {
        text.lines().enumerate().filter_map(|(i, line)| {
            let line = line.split('#').next().unwrap_or("").trim();
            let mut words = line.split_whitespace();
            words.next().map(|keyword| (i + 1, keyword, words))
        })
    };
    // Positive indices may name data given further down; negative ones count back from
    // the statement.
    let mut totals = [0usize; 3];
    for (_, keyword, _) in statements() {
        if let Some(k) = kind(keyword) {
            totals[k] += 1;
        }
    }
    let mut seen = [0usize; 3];
    let mut faces = Vec::new();
    for (line, keyword, words) in statements() {
        let at = |what: String| format!("line {line}: {keyword}: {what}");
        match keyword {
            "v" | "vt" | "vn" => {
                let numbers: Vec<&str> = words.collect();
                let least = if keyword == "vt" { 1 } else { 3 };
                if numbers.len() < least {
                    return Err(at(format!(
                        "{least} numbers expected, got {}",
                        numbers.len()
                    )));
                }
                for word in numbers {
                    match word.parse::<f32>() {
                        Ok(x) if x.is_finite() => {}
                        Ok(_) => return Err(at(format!("{word} is not a finite number"))),
                        Err(_) => return Err(at(format!("{word} is not a number"))),
                    }
                }
                if let Some(k) = kind(keyword) {
                    seen[k] += 1;
                }
            }
            "f" => {
                let corners: Vec<&str> = words.collect();
                if corners.len() < 3 {
                    return Err(at(format!(
                        "a face needs at least 3 corners, got {}",
                        corners.len()
                    )));
                }
                for corner in corners {
                    check_corner(corner, &seen, &totals).map_err(at)?;
                }
                faces.push(line);
            }
            _ => {}
        }
    }
    Ok(FaceLines(faces))
}

/// The MTL `text` with its colour statements (`Ka`, `Kd`, `Ks`, `Ke`, `Tf`) checked and
/// written out in full: one number stands for three equal ones, as the format allows (`tobj`
/// panicked on fewer than three); more numbers than three, or words that are not numbers,
/// are an error `line N: what is wrong`. Spectral (`spectral`) and CIE (`xyz`) colours are
/// refused.
pub(super) fn check_mtl(text: &str) -> Result<String, String> {
    let mut out = String::with_capacity(text.len());
    for (i, line) in text.lines().enumerate() {
        let code = line.split('#').next().unwrap_or("");
        let mut words = code.split_whitespace();
        let keyword = words.next().unwrap_or("");
        if !["Ka", "Kd", "Ks", "Ke", "Tf"].contains(&keyword) {
            out.push_str(line);
            out.push('\n');
            continue;
        }
        let at = |what: String| format!("line {}: {keyword}: {what}", i + 1);
        let numbers = words
            .map(|w| match w.parse::<f32>() {
                Ok(x) if x.is_finite() => Ok(w),
                _ => Err(at(format!("{w} is not a finite number"))),
            })
            .collect::<Result<Vec<&str>, String>>()?;
        let rgb = match numbers[..] {
            [grey] => [grey; 3],
            [r, g, b] => [r, g, b],
            _ => {
                return Err(at(format!(
                    "1 or 3 numbers expected, got {}",
                    numbers.len()
                )));
            }
        };
        out.push_str(&format!("{keyword} {} {} {}\n", rgb[0], rgb[1], rgb[2]));
    }
    Ok(out)
}

/// Index of the counter for a data statement: positions, texture coordinates, normals.
fn kind(keyword: &str) -> Option<usize> {
    ["v", "vt", "vn"].iter().position(|k| *k == keyword)
}

/// Checks one face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`.
fn check_corner(corner: &str, seen: &[usize; 3], totals: &[usize; 3]) -> Result<(), String> {
    const NAMES: [&str; 3] = ["vertex", "texture coordinate", "normal"];
    let parts: Vec<&str> = corner.split('/').collect();
    if parts.len() > 3 || parts[0].is_empty() {
        return Err(format!(
            "corner \"{corner}\" is not v, v/vt, v//vn or v/vt/vn"
        ));
    }
    for (k, part) in parts.iter().enumerate().filter(|(_, p)| !p.is_empty()) {
        let index: i64 = part
            .parse()
            .map_err(|_| format!("corner \"{corner}\": {part} is not an index"))?;
        let exists = match index {
            0 => false,
            i if i > 0 => i as u64 <= totals[k] as u64,
            i => i.unsigned_abs() <= seen[k] as u64,
        };
        if !exists {
            let count = if index < 0 { seen[k] } else { totals[k] };
            return Err(format!(
                "corner \"{corner}\": {} {index} does not exist ({count} given{})",
                NAMES[k],
                if index < 0 { " so far" } else { "" }
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_are_found_by_line_and_bad_statements_named() {
        let text = "# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\nf 1 2 3 4\nf -4 -3 -2\n";
        assert_eq!(check(text).unwrap().0, vec![7, 8]);
        let cases = [
            ("v 0 0\n", "line 1: v: 3 numbers expected, got 2"),
            ("v 0 zero 0\n", "line 1: v: zero is not a number"),
            ("v 0 inf 0\n", "line 1: v: inf is not a finite number"),
            (
                "v 0 0 0\nv 1 0 0\nf 1 2\n",
                "line 3: f: a face needs at least 3",
            ),
            ("v 0 0 0\nf 1 2 3\n", "vertex 2 does not exist (1 given)"),
            (
                "v 0 0 0\nf 1 1 -2\n",
                "vertex -2 does not exist (1 given so far)",
            ),
            (
                "v 0 0 0\nf 1/1 1 1\n",
                "texture coordinate 1 does not exist",
            ),
            ("v 0 0 0\nf 1//x 1 1\n", "x is not an index"),
            ("v 0 0 0\nf 0 1 1\n", "vertex 0 does not exist"),
        ];
        for (text, says) in cases {
            let err = check(text).unwrap_err();
            assert!(err.contains(says), "{text:?}: {err}");
        }
        assert_eq!(
            check_mtl("Kd 0.6\nKs 1 0 0 # red\n").unwrap(),
            "Kd 0.6 0.6 0.6\nKs 1 0 0\n"
        );
        assert!(
            check_mtl("newmtl a\nKd 0.6 0.5\n")
                .unwrap_err()
                .contains("line 2: Kd: 1 or 3")
        );
        assert!(
            check_mtl("Ke x\n")
                .unwrap_err()
                .contains("x is not a finite number")
        );
        assert!(check_mtl("Ka\n").unwrap_err().contains("got 0"));
        // Data given after the face that names it is allowed (positive indices).
        assert!(check("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").is_ok());
    }
}
