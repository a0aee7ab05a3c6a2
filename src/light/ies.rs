//! IES LM-63 photometric files (the 1991, 1995, 2002 and 2019 layouts; type C photometry).
//!
//! A file is free text up to a `TILT=` line (the version line and `[KEYWORD] value` lines),
//! then numbers separated by blanks, commas or line breaks: the number of lamps, lumens per
//! lamp (-1 for absolute photometry), the candela multiplier, the numbers of vertical and
//! horizontal angles, the photometric type (1 = C), the units and the luminous opening's
//! width, length and height; the ballast factor, a value for future use (the ballast-lamp
//! factor of older versions) and the input watts; the vertical angles, the horizontal angles,
//! and the candela values, all vertical angles of the first horizontal angle first.
//!
//! No crate fits: `eulumdat` is AGPL and `lidrs` states no licence. This parser checks what
//! the renderer relies on and reports the file and line of the first fault.

use std::path::{Path, PathBuf};

/// A parsed type C photometric file. Angles in degrees; `candela[h * vertical.len() + v]`.
#[derive(Clone, Debug, PartialEq)]
pub struct IesData {
    pub lamps: u32,
    /// Rated lumens per lamp; -1 for absolute photometry (LED luminaires).
    pub lumens_per_lamp: f64,
    pub multiplier: f64,
    pub ballast_factor: f64,
    pub input_watts: f64,
    pub vertical: Vec<f64>,
    pub horizontal: Vec<f64>,
    pub candela: Vec<f64>,
}

impl IesData {
    /// Absolute intensity (cd) of a table entry: candela x multiplier x ballast factor.
    pub fn intensity(&self, h: usize, v: usize) -> f64 {
        self.candela[h * self.vertical.len() + v] * self.multiplier * self.ballast_factor
    }
}

/// Why a file is not a photometric file brume can use: its path, the line (1-based) and what
/// is wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}:{line}: {message}", file.display())]
pub struct IesError {
    pub file: PathBuf,
    pub line: usize,
    pub message: String,
}

/// Largest table accepted (angles per axis): real files have at most a few hundred.
const MAX_ANGLES: usize = 10_000;

/// Reads and parses `path`.
pub fn load(path: &Path) -> Result<IesData, IesError> {
    let bytes = std::fs::read(path).map_err(|e| IesError {
        file: path.to_path_buf(),
        line: 0,
        message: format!("cannot read: {e}"),
    })?;
    // Files come from many tools; Latin-1 text in the keywords is common and harmless.
    let text = String::from_utf8_lossy(&bytes);
    parse(&text, path)
}

/// Numbers after the TILT line, each with its line.
struct Numbers<'a> {
    tokens: Vec<(usize, &'a str)>,
    next: usize,
    file: &'a Path,
    last_line: usize,
}

impl Numbers<'_> {
    fn fail(&self, line: usize, message: impl Into<String>) -> IesError {
        IesError {
            file: self.file.to_path_buf(),
            line,
            message: message.into(),
        }
    }

    fn number(&mut self, what: &str) -> Result<(usize, f64), IesError> {
        let Some(&(line, tok)) = self.tokens.get(self.next) else {
            return Err(self.fail(self.last_line, format!("the file ends before {what}")));
        };
        self.next += 1;
        match tok.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((line, v)),
            // The token is not quoted: a file's content is never echoed in messages.
            _ => Err(self.fail(line, format!("{what} is not a finite number"))),
        }
    }

    fn count(&mut self, what: &str, min: usize) -> Result<usize, IesError> {
        let (line, v) = self.number(what)?;
        if v.fract() != 0.0 || v < min as f64 || v > MAX_ANGLES as f64 {
            return Err(self.fail(
                line,
                format!("{what} must be a whole number in {min}..={MAX_ANGLES}, got {v}"),
            ));
        }
        Ok(v as usize)
    }

    fn positive(&mut self, what: &str) -> Result<f64, IesError> {
        let (line, v) = self.number(what)?;
        if v <= 0.0 {
            return Err(self.fail(line, format!("{what} must be > 0, got {v}")));
        }
        Ok(v)
    }

    /// `n` angles, strictly increasing, within `[lo, hi]`.
    fn angles(&mut self, what: &str, n: usize, lo: f64, hi: f64) -> Result<Vec<f64>, IesError> {
        let mut out: Vec<f64> = Vec::with_capacity(n);
        for i in 0..n {
            let (line, v) = self.number(what)?;
            if !(lo..=hi).contains(&v) {
                return Err(self.fail(line, format!("{what} {v} is outside [{lo}, {hi}]")));
            }
            if let Some(&prev) = out.last()
                && v <= prev
            {
                return Err(self.fail(
                    line,
                    format!("{what} must increase: {v} follows {prev} (angle {})", i + 1),
                ));
            }
            out.push(v);
        }
        Ok(out)
    }
}

/// Parses the text of a photometric file (`file` names it in errors).
pub fn parse(text: &str, file: &Path) -> Result<IesData, IesError> {
    let fail = |line: usize, message: String| IesError {
        file: file.to_path_buf(),
        line,
        message,
    };
    let lines: Vec<&str> = text.lines().collect();
    let Some(tilt) = lines
        .iter()
        .position(|l| l.trim_start().to_ascii_uppercase().starts_with("TILT"))
    else {
        return Err(fail(
            lines.len().max(1),
            "no `TILT=` line: not an IES LM-63 photometric file".into(),
        ));
    };
    let value = lines[tilt]
        .split_once('=')
        .map(|(_, v)| v.trim())
        .unwrap_or("");
    if !value.eq_ignore_ascii_case("NONE") {
        return Err(fail(
            tilt + 1,
            "TILT is not NONE: lamp output that varies with the luminaire's tilt is not \
             supported (only TILT=NONE)"
                .into(),
        ));
    }
    let tokens: Vec<(usize, &str)> = lines[tilt + 1..]
        .iter()
        .enumerate()
        .flat_map(|(i, l)| {
            l.split(|c: char| c.is_whitespace() || c == ',')
                .filter(|t| !t.is_empty())
                .map(move |t| (tilt + 2 + i, t))
        })
        .collect();
    let mut nums = Numbers {
        tokens,
        next: 0,
        file,
        last_line: lines.len().max(1),
    };
    read_numbers(&mut nums)
}

fn read_numbers(nums: &mut Numbers) -> Result<IesData, IesError> {
    let lamps = nums.count("the number of lamps", 1)? as u32;
    let (line, lumens_per_lamp) = nums.number("the lumens per lamp")?;
    if !(lumens_per_lamp > 0.0 || lumens_per_lamp == -1.0) {
        return Err(nums.fail(
            line,
            format!(
                "lumens per lamp must be > 0 (or -1 for absolute photometry), got {lumens_per_lamp}"
            ),
        ));
    }
    let multiplier = nums.positive("the candela multiplier")?;
    let nv = nums.count("the number of vertical angles", 2)?;
    let nh = nums.count("the number of horizontal angles", 1)?;
    read_type_and_units(nums)?;
    for what in [
        "the luminous width",
        "the luminous length",
        "the luminous height",
    ] {
        nums.number(what)?;
    }
    let ballast_factor = nums.positive("the ballast factor")?;
    nums.number("the ballast-lamp factor (future use)")?;
    let (_, input_watts) = nums.number("the input watts")?;
    let vertical = nums.angles("vertical angle", nv, 0.0, 180.0)?;
    let start = nums.tokens.get(nums.next).map_or(nums.last_line, |t| t.0);
    let horizontal = nums.angles("horizontal angle", nh, 0.0, 360.0)?;
    check_horizontal(nums, start, &horizontal)?;
    let candela = read_candela(nums, nv, nh)?;
    Ok(IesData {
        lamps,
        lumens_per_lamp,
        multiplier,
        ballast_factor,
        input_watts,
        vertical,
        horizontal,
        candela,
    })
}

/// The photometric type (only C is supported) and the units type (feet or metres).
fn read_type_and_units(nums: &mut Numbers) -> Result<(), IesError> {
    let (line, kind) = nums.number("the photometric type")?;
    let name = match kind {
        1.0 => None,
        2.0 => Some("B"),
        3.0 => Some("A"),
        _ => {
            let m = format!("photometric type must be 1, 2 or 3, got {kind}");
            return Err(nums.fail(line, m));
        }
    };
    if let Some(name) = name {
        let m = format!("photometric type {kind} ({name}) is not supported: only type C (1)");
        return Err(nums.fail(line, m));
    }
    let (line, units) = nums.number("the units type")?;
    if units != 1.0 && units != 2.0 {
        return Err(nums.fail(
            line,
            format!("units type must be 1 (feet) or 2 (metres), got {units}"),
        ));
    }
    Ok(())
}

/// The table's `nv * nh` candela values, and nothing after them.
fn read_candela(nums: &mut Numbers, nv: usize, nh: usize) -> Result<Vec<f64>, IesError> {
    let mut candela = Vec::with_capacity(nv * nh);
    for i in 0..nv * nh {
        let what = format!(
            "candela value {} of {} ({nh} horizontal x {nv} vertical angles)",
            i + 1,
            nv * nh
        );
        let (line, v) = nums.number(&what)?;
        if v < 0.0 {
            return Err(nums.fail(line, format!("{what} is negative: {v}")));
        }
        candela.push(v);
    }
    if let Some(&(line, tok)) = nums.tokens.get(nums.next) {
        return Err(nums.fail(
            line,
            format!(
                "`{tok}` after the last of the {} candela values the header announces \
                 ({nh} horizontal x {nv} vertical angles)",
                nv * nh
            ),
        ));
    }
    Ok(candela)
}

/// Type C horizontal angles start at 0 and end at 0 (rotational symmetry), 90 (symmetry in each
/// quadrant), 180 (bilateral symmetry about the 0-180 plane) or 360; a full table that stops
/// short of 360 (0 .. 350) wraps around to 0.
fn check_horizontal(nums: &Numbers, line: usize, h: &[f64]) -> Result<(), IesError> {
    if h[0] != 0.0 {
        return Err(nums.fail(
            line,
            format!("type C horizontal angles start at 0, got {}", h[0]),
        ));
    }
    let last = h[h.len() - 1];
    if last == 0.0 || last == 90.0 || last >= 180.0 {
        Ok(())
    } else {
        Err(nums.fail(
            line,
            format!(
                "the last horizontal angle must be 0, 90, 180 or 360 (or above 180 for a full \
                 table), got {last}"
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "IESNA:LM-63-2002\n[TEST] unit\n[MANUFAC] brume\nTILT=NONE\n\
        1 1000 1 3 2 1 2 0.1 0.1 0\n1.0 1.0 50\n0 45 90\n0 180\n100 80 0\n120, 90, 10\n";

    fn err(text: &str) -> IesError {
        parse(text, Path::new("lamp.ies")).unwrap_err()
    }

    #[test]
    fn reads_a_small_file() {
        let d = parse(GOOD, Path::new("lamp.ies")).unwrap();
        assert_eq!(d.vertical, vec![0.0, 45.0, 90.0]);
        assert_eq!(d.horizontal, vec![0.0, 180.0]);
        assert_eq!(d.intensity(1, 1), 90.0);
        assert_eq!(
            (d.lamps, d.lumens_per_lamp, d.input_watts),
            (1, 1000.0, 50.0)
        );
    }

    #[test]
    fn faults_name_their_line() {
        let e = err(&GOOD.replace("TILT=NONE", "TILT=INCLUDE"));
        assert_eq!(e.line, 4, "{e}");
        assert!(
            e.to_string().starts_with("lamp.ies:4: TILT is not NONE"),
            "{e}"
        );
        let e = err(&GOOD.replace("0 45 90", "0 45 40"));
        assert_eq!(e.line, 7, "{e}");
        assert!(e.message.contains("must increase"), "{e}");
        let e = err(&GOOD.replace("120, 90, 10\n", "120, 90\n"));
        assert!(
            e.message.contains("ends before candela value 6 of 6"),
            "{e}"
        );
        let e = err(&GOOD.replace("120, 90, 10", "120, 90, 10 7"));
        assert_eq!(e.line, 10, "{e}");
        let e = err(&GOOD.replace("100 80 0", "100 -80 0"));
        assert_eq!(e.line, 9, "{e}");
        let e = err(&GOOD.replace("1 2 0.1", "3 2 0.1"));
        assert!(e.message.contains("type 3 (A)"), "{e}");
        assert_eq!(e.line, 5);
        let e = err(&GOOD.replace("0 180\n", "0 120\n"));
        assert!(e.message.contains("last horizontal angle"), "{e}");
        let e = err(&GOOD.replace("1.0 1.0 50", "1.0 x 50"));
        assert_eq!(e.line, 6, "{e}");
        assert!(e.message.contains("is not a finite number"), "{e}");
    }

    /// A file named by mistake (a scene's `profile`, a `--set`) never has its text printed:
    /// errors give the line and what was expected.
    #[test]
    fn faults_do_not_echo_the_file() {
        for bad in [
            GOOD.replace("TILT=NONE", "TILT=secret-text"),
            GOOD.replace("1.0 1.0 50", "1.0 secret-text 50"),
            GOOD.replace("0 180\n", "0 secret-text\n"),
        ] {
            let e = err(&bad).to_string();
            assert!(!e.contains("secret"), "{e}");
        }
        let e = err("just text\n");
        assert!(e.message.contains("no `TILT=` line"), "{e}");
    }
}
