//! The statements of an OBJ file, line by line: vertex data, faces with their line numbers, the
//! material libraries named, and what was skipped. Errors are "FILE:LINE: …" in words.

use anyhow::{bail, Result};
use rust_i18n::t;

/// One corner of a face: 0-based indices into the position, texcoord and normal lists.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Corner {
    pub v: usize,
    pub vt: Option<usize>,
    pub vn: Option<usize>,
}

/// A face with 3 or more corners and the line it was written on.
#[derive(Clone, Debug)]
pub struct Face {
    pub corners: Vec<Corner>,
    pub line: usize,
}

/// Statements that were read but are not surfaces: how many, and the first and last lines.
#[derive(Clone, Copy, Debug, Default)]
pub struct Skipped {
    pub count: usize,
    pub first: usize,
    pub last: usize,
}

impl Skipped {
    fn add(&mut self, line: usize) {
        if self.count == 0 {
            self.first = line;
        }
        self.count += 1;
        self.last = line;
    }
}

/// What an OBJ file holds.
#[derive(Debug, Default)]
pub struct ObjFile {
    pub positions: Vec<[f32; 3]>,
    pub texcoords: Vec<[f32; 2]>,
    pub normals: Vec<[f32; 3]>,
    pub faces: Vec<Face>,
    /// `mtllib` arguments with their line.
    pub mtllibs: Vec<(String, usize)>,
    /// `l` polylines.
    pub lines: Skipped,
    /// `p` points.
    pub points: Skipped,
    /// `f` with fewer than 3 corners.
    pub short_faces: Skipped,
    /// Free-form geometry (curves and surfaces), which the engine does not draw.
    pub free_form: Skipped,
    /// Statements no OBJ reader knows (the first one's keyword is kept).
    pub unknown: Skipped,
    pub unknown_keyword: String,
}

/// Keywords of the OBJ format that carry nothing the engine draws (grouping, smoothing, materials,
/// render attributes).
const IGNORED: &[&str] = &[
    "o",
    "g",
    "s",
    "mg",
    "usemtl",
    "usemap",
    "maplib",
    "lod",
    "bevel",
    "c_interp",
    "d_interp",
    "shadow_obj",
    "trace_obj",
    "ctech",
    "stech",
    "vp",
];

/// Free-form geometry keywords.
const FREE_FORM: &[&str] = &[
    "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp",
    "end", "con",
];

/// The logical lines of `text` with their (first) line numbers: a line ending in `\` continues on
/// the next one.
fn logical_lines(text: &str) -> impl Iterator<Item = (usize, String)> + '_ {
    let mut lines = text.lines().enumerate().peekable();
    std::iter::from_fn(move || {
        let (i, first) = lines.next()?;
        let mut line = first.to_string();
        while line.ends_with('\\') {
            line.pop();
            match lines.next() {
                Some((_, next)) => {
                    line.push(' ');
                    line.push_str(next);
                }
                None => break,
            }
        }
        Some((i + 1, line))
    })
}

/// Parses the text of the OBJ file `shown` (the name used in messages).
pub fn parse(text: &str, shown: &str) -> Result<ObjFile> {
    let mut obj = ObjFile::default();
    for (n, line) in logical_lines(text) {
        let place = format!("{shown}:{n}");
        // A comment runs from a `#` that starts a word to the end of the line.
        let content = match line.find('#') {
            Some(i) if i == 0 || line[..i].ends_with(char::is_whitespace) => &line[..i],
            _ => &line[..],
        };
        let mut words = content.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let args: Vec<&str> = words.collect();
        match keyword {
            "v" => {
                let x = numbers(&args, 3, 7, "v", &place)?;
                let mut p = [x[0], x[1], x[2]];
                // x y z w: a homogeneous point.
                if x.len() == 4 {
                    if x[3] == 0.0 {
                        bail!("{}", t!("obj.w_zero", place = place));
                    }
                    p = p.map(|c| c / x[3]);
                }
                obj.positions.push(p);
            }
            "vt" => {
                let x = numbers(&args, 1, 3, "vt", &place)?;
                obj.texcoords.push([x[0], x.get(1).copied().unwrap_or(0.0)]);
            }
            "vn" => {
                let x = numbers(&args, 3, 3, "vn", &place)?;
                obj.normals.push([x[0], x[1], x[2]]);
            }
            "f" | "fo" => {
                if args.len() < 3 {
                    obj.short_faces.add(n);
                    continue;
                }
                let corners = args
                    .iter()
                    .map(|a| corner(a, &obj, &place))
                    .collect::<Result<Vec<_>>>()?;
                obj.faces.push(Face { corners, line: n });
            }
            "l" => obj.lines.add(n),
            "p" => obj.points.add(n),
            "mtllib" => {
                let rest = content.trim_start()[keyword.len()..].trim();
                if !rest.is_empty() {
                    obj.mtllibs.push((rest.to_string(), n));
                }
            }
            k if IGNORED.contains(&k) => {}
            k if FREE_FORM.contains(&k) => obj.free_form.add(n),
            k => {
                if obj.unknown.count == 0 {
                    obj.unknown_keyword = k.chars().take(40).collect();
                }
                obj.unknown.add(n);
            }
        }
    }
    Ok(obj)
}

/// `min`..=`max` finite numbers.
fn numbers(args: &[&str], min: usize, max: usize, what: &str, place: &str) -> Result<Vec<f32>> {
    if args.len() < min || args.len() > max {
        let count = args.len();
        bail!(
            "{}",
            t!(
                "obj.value_count",
                place = place,
                what = what,
                min = min,
                max = max,
                count = count
            )
        );
    }
    args.iter()
        .map(|a| match a.parse::<f32>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => bail!("{}", t!("obj.not_a_number", place = place, value = a)),
        })
        .collect()
}

/// One `v`, `v/vt`, `v//vn` or `v/vt/vn` corner, checked against what is defined so far.
fn corner(arg: &str, obj: &ObjFile, place: &str) -> Result<Corner> {
    let mut parts = arg.split('/');
    let mut index = |what: &str, count: usize, required: bool| -> Result<Option<usize>> {
        let part = parts.next().unwrap_or("");
        if part.is_empty() && !required {
            return Ok(None);
        }
        let bad = || anyhow::anyhow!("{}", t!("obj.bad_corner", place = place, corner = arg));
        let i: i64 = part.parse().map_err(|_| bad())?;
        // 1-based, or negative: counted back from the last one defined so far.
        let resolved = if i > 0 { i - 1 } else { count as i64 + i };
        if i == 0 || resolved < 0 || resolved >= count as i64 {
            bail!(
                "{}",
                t!(
                    "obj.index_out_of_range",
                    place = place,
                    what = what,
                    index = i,
                    count = count
                )
            );
        }
        Ok(Some(resolved as usize))
    };
    let v = index("v", obj.positions.len(), true)?.unwrap_or_default();
    let vt = index("vt", obj.texcoords.len(), false)?;
    let vn = index("vn", obj.normals.len(), false)?;
    if parts.next().is_some() {
        bail!("{}", t!("obj.bad_corner", place = place, corner = arg));
    }
    Ok(Corner { v, vt, vn })
}
