//! C `printf` number formatting, byte for byte as glibc writes it.
//!
//! LAMMPS turns numbers into text with `printf`: `${v}` of an equal-style variable is
//! `%.15g`, an immediate `$(...)` is `%.20g`, format-style variables and `thermo_modify format`
//! take a user's conversion. Rust's `{:.N}` and `{:.Ne}` are exact and round half to even on
//! the exact binary value, as glibc does, so the digits come from them and this file only
//! reproduces the layout rules of C (`%g` style choice, trailing zeros, exponent with at least
//! two digits, flags, width, `inf`/`nan` with their sign).

/// The largest width and precision of a conversion dmhs formats: 4096. Larger ones are refused
/// with an error (C's `printf` takes up to INT_MAX, but LAMMPS formats into buffers of 64 to a
/// few hundred characters and Rust's formatting stops at a precision of 65535). 4096 leaves room
/// for every digit of any double (`%.1074f` prints the smallest subnormal exactly).
pub const MAX_FIELD: usize = 4096;

/// One parsed C conversion: `%[flags][width][.precision]conv`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Conversion {
    pub left: bool,
    pub plus: bool,
    pub space: bool,
    pub zero: bool,
    pub alt: bool,
    pub width: usize,
    pub precision: Option<usize>,
    /// One of `f F e E g G d i`.
    pub conv: char,
}

/// Identical to C `printf("%.{precision}g", x)` with glibc (including `inf`, `-inf`, `nan`,
/// `-nan` and `-0`).
pub fn format_g(x: f64, precision: usize) -> String {
    format_one(x, &Conversion { precision: Some(precision), conv: 'g', ..Conversion::default() })
}

/// Format `x` with a text holding exactly one C conversion (`%f %F %e %E %g %G %d %i` with flags
/// `-+ 0#`, a width and a precision; `%%` is a literal percent sign). Text around the conversion
/// is kept. A length modifier (`l`, `ll`, `L`, `h`) is accepted and ignored. Text without a
/// conversion is returned as is (with `%%` turned into `%`).
pub fn format_printf(fmt: &str, x: f64) -> Result<String, String> {
    let mut out = String::new();
    let mut found = false;
    let b = fmt.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] != b'%' {
            // copy one UTF-8 character
            let ch = fmt[i..].chars().next().unwrap_or('?');
            out.push(ch);
            i += ch.len_utf8();
            continue;
        }
        if b.get(i + 1) == Some(&b'%') {
            out.push('%');
            i += 2;
            continue;
        }
        let (spec, next) = parse_conversion(fmt, i)?;
        if found {
            return Err(format!("format `{fmt}` has more than one conversion; only one number is formatted"));
        }
        found = true;
        out.push_str(&format_one(x, &spec));
        i = next;
    }
    Ok(out)
}

/// Parse the conversion starting at byte `start` (a `%`); returns it and the byte after it.
pub fn parse_conversion(fmt: &str, start: usize) -> Result<(Conversion, usize), String> {
    let b = fmt.as_bytes();
    let mut i = start + 1;
    let mut c = Conversion::default();
    while i < b.len() {
        match b[i] {
            b'-' => c.left = true,
            b'+' => c.plus = true,
            b' ' => c.space = true,
            b'0' => c.zero = true,
            b'#' => c.alt = true,
            _ => break,
        }
        i += 1;
    }
    // a width or precision: digits, at most MAX_FIELD
    let digits = |i: &mut usize, what: &str| {
        let s = *i;
        while *i < b.len() && b[*i].is_ascii_digit() {
            *i += 1;
        }
        let text = &fmt[s..*i];
        match text.parse::<usize>() {
            Ok(n) if n <= MAX_FIELD => Ok(n),
            _ if text.is_empty() => Ok(0),
            _ => Err(format!("{what} {text} in format `{fmt}` is too large: dmhs formats numbers with a {what} of at most {MAX_FIELD}")),
        }
    };
    c.width = digits(&mut i, "width")?;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        c.precision = Some(digits(&mut i, "precision")?);
    }
    // length modifiers do not change how a double is printed
    while i < b.len() && matches!(b[i], b'l' | b'L' | b'h') {
        i += 1;
    }
    match b.get(i) {
        Some(&ch) if b"fFeEgGdi".contains(&ch) => {
            c.conv = ch as char;
            Ok((c, i + 1))
        }
        _ => Err(format!(
            "invalid conversion `{}` in format `{fmt}`; expected one of %f %e %E %g %G %d %i",
            // up to the end of the offending character (which may take several bytes)
            &fmt[start..fmt[i..].chars().next().map_or(fmt.len(), |ch| i + ch.len_utf8())]
        )),
    }
}

/// Format one number with one conversion.
pub fn format_one(x: f64, c: &Conversion) -> String {
    let negative = x.is_sign_negative();
    let sign = if negative {
        "-"
    } else if c.plus {
        "+"
    } else if c.space {
        " "
    } else {
        ""
    };
    let upper = c.conv.is_ascii_uppercase();
    if matches!(c.conv, 'd' | 'i') {
        return format_int(x, c);
    }
    if !x.is_finite() {
        let body = match (x.is_nan(), upper) {
            (true, false) => "nan",
            (true, true) => "NAN",
            (false, false) => "inf",
            (false, true) => "INF",
        };
        // glibc pads inf/nan with spaces even with the 0 flag
        return pad(sign, body, c.width, c.left, false);
    }
    let a = x.abs();
    // parse_conversion refuses larger precisions; Rust's formatting panics above 65535
    let p = c.precision.unwrap_or(6).min(MAX_FIELD);
    let body = match c.conv.to_ascii_lowercase() {
        'f' => fixed(a, p, c.alt),
        'e' => exponential(a, p, c.alt, upper),
        _ => general(a, p, c.alt, upper),
    };
    pad(sign, &body, c.width, c.left, c.zero)
}

/// `%d`: the value truncated toward zero (C would need an integer argument).
fn format_int(x: f64, c: &Conversion) -> String {
    let v = if x.is_nan() { 0 } else { x.trunc() as i64 };
    let sign = if v < 0 {
        "-"
    } else if c.plus {
        "+"
    } else if c.space {
        " "
    } else {
        ""
    };
    let mut digits = v.unsigned_abs().to_string();
    if let Some(p) = c.precision {
        if p == 0 && v == 0 {
            digits.clear();
        }
        while digits.len() < p.min(MAX_FIELD) {
            digits.insert(0, '0');
        }
    }
    // the 0 flag is ignored when a precision is given
    pad(sign, &digits, c.width, c.left, c.zero && c.precision.is_none())
}

fn pad(sign: &str, body: &str, width: usize, left: bool, zero: bool) -> String {
    let width = width.min(MAX_FIELD);
    let len = sign.len() + body.len();
    if len >= width {
        return format!("{sign}{body}");
    }
    let fill = width - len;
    if left {
        format!("{sign}{body}{}", " ".repeat(fill))
    } else if zero {
        format!("{sign}{}{body}", "0".repeat(fill))
    } else {
        format!("{}{sign}{body}", " ".repeat(fill))
    }
}

/// `%.pf` of a non-negative finite number.
fn fixed(a: f64, p: usize, alt: bool) -> String {
    let mut s = format!("{:.*}", p, a);
    if alt && p == 0 {
        s.push('.');
    }
    s
}

/// Digits `d.ddd` (p after the point) and decimal exponent of a non-negative finite number,
/// rounded as `%.pe` rounds.
fn sci_parts(a: f64, p: usize) -> (String, i32) {
    let s = format!("{:.*e}", p, a);
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    (m.to_string(), e.parse::<i32>().unwrap_or(0))
}

fn exp_suffix(e: i32, upper: bool) -> String {
    let mark = if upper { 'E' } else { 'e' };
    let sign = if e < 0 { '-' } else { '+' };
    format!("{mark}{sign}{:02}", e.unsigned_abs())
}

/// `%.pe` of a non-negative finite number.
fn exponential(a: f64, p: usize, alt: bool, upper: bool) -> String {
    let (mut m, e) = sci_parts(a, p);
    if alt && p == 0 {
        m.push('.');
    }
    m + &exp_suffix(e, upper)
}

/// `%.pg` of a non-negative finite number: `%e` or `%f` chosen by the exponent, then trailing
/// zeros removed (unless `#`).
fn general(a: f64, p: usize, alt: bool, upper: bool) -> String {
    let p = if p == 0 { 1 } else { p };
    let (m, x) = sci_parts(a, p - 1);
    if (x as i64) < p as i64 && x >= -4 {
        let s = format!("{:.*}", (p as i64 - 1 - x as i64) as usize, a);
        if alt {
            if s.contains('.') { s } else { s + "." }
        } else {
            strip_zeros(&s).to_string()
        }
    } else {
        let m = if alt {
            if m.contains('.') { m } else { m + "." }
        } else {
            strip_zeros(&m).to_string()
        };
        m + &exp_suffix(x, upper)
    }
}

/// Remove trailing zeros of a fraction, and the point if nothing is left after it.
fn strip_zeros(s: &str) -> &str {
    if !s.contains('.') {
        return s;
    }
    s.trim_end_matches('0').trim_end_matches('.')
}

/// True if `fmt` is accepted by LAMMPS as the format of a `format`-style variable:
/// the whole text is one conversion `%[ ][-][width][.precision]` with `e f g E F G`
/// (checked with LAMMPS 22 Jul 2025: `%-10.4f`, `% .2g`, `%08.3f`, `%f` pass; `%+.3e`, `%#.3g`,
/// `%.3f units`, `%d` fail).
pub fn is_format_style_spec(fmt: &str) -> bool {
    let b = fmt.as_bytes();
    let mut i = 0;
    let eat = |c: u8, i: &mut usize| {
        if b.get(*i) == Some(&c) {
            *i += 1;
            true
        } else {
            false
        }
    };
    if !eat(b'%', &mut i) {
        return false;
    }
    eat(b' ', &mut i);
    eat(b'-', &mut i);
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    if b.get(i) == Some(&b'.') {
        i += 1;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
    }
    i + 1 == b.len() && b"efgEFG".contains(&b[i])
}

/// True if `fmt` is accepted by LAMMPS after the colon of an immediate `$(expr:fmt)`: somewhere
/// in it a `%`, spaces or digits, a point, at least one digit and one of `e f g E F G`
/// (LAMMPS 22 Jul 2025: `%.3f units`, `%10.4f`, `% .2g` pass; `%f`, `%-10.4f`, `%d` fail).
pub fn is_immediate_format_spec(fmt: &str) -> bool {
    let b = fmt.as_bytes();
    (0..b.len()).any(|start| {
        if b[start] != b'%' {
            return false;
        }
        let mut i = start + 1;
        while i < b.len() && (b[i].is_ascii_digit() || b[i] == b' ') {
            i += 1;
        }
        if b.get(i) != Some(&b'.') {
            return false;
        }
        i += 1;
        let d = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i > d && i < b.len() && b"efgEFG".contains(&b[i])
    })
}

/// The shortest form that reads back to `x`, as LAMMPS' messages print a double with fmt's
/// `{}`: fixed notation from 1e-4 up to 1e16, else `1.5e-05` / `1e+16`.
pub fn shortest(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    let a = x.abs();
    if !x.is_finite() || a == 0.0 || (1e-4..1e16).contains(&a) {
        return format!("{x}");
    }
    let s = format!("{x:e}");
    let (mantissa, exp) = s.split_once('e').expect("{:e} has an exponent");
    let (sign, digits) = exp.strip_prefix('-').map_or(("+", exp), |d| ("-", d));
    format!("{mantissa}e{sign}{digits:0>2}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn g_layout() {
        assert_eq!(format_g(0.0, 15), "0");
        assert_eq!(format_g(-0.0, 15), "-0");
        assert_eq!(format_g(1.0 / 3.0, 15), "0.333333333333333");
        assert_eq!(format_g(1.0 / 3.0, 20), "0.33333333333333331483");
        assert_eq!(format_g(1e15, 15), "1e+15");
        assert_eq!(format_g(1e15, 20), "1000000000000000");
        assert_eq!(format_g(1e21, 20), "1e+21");
        assert_eq!(format_g(1e-5, 15), "1e-05");
        assert_eq!(format_g(1e-5, 20), "1.0000000000000000818e-05");
        assert_eq!(format_g(0.0001, 15), "0.0001");
        assert_eq!(format_g(123456789012345678.0, 20), "123456789012345680");
        assert_eq!(format_g(1.2345678901234567e29, 15), "1.23456789012346e+29");
        assert_eq!(format_g(100.0, 1), "1e+02");
        assert_eq!(format_g(0.5, 0), "0.5");
        assert_eq!(format_g(2.5, 1), "2");
        assert_eq!(format_g(f64::INFINITY, 15), "inf");
        assert_eq!(format_g(f64::NEG_INFINITY, 15), "-inf");
        assert_eq!(format_g(f64::NAN, 15), "nan");
        assert_eq!(format_g(-f64::NAN, 15), "-nan");
        assert_eq!(format_g(1e-310, 15), "9.99999999999997e-311");
        assert_eq!(format_g(5e-324, 20), "4.9406564584124654418e-324");
        assert_eq!(format_g(f64::MAX, 15), "1.79769313486232e+308");
    }

    #[test]
    fn printf_conversions() {
        let pi = std::f64::consts::PI;
        // observed with LAMMPS 22 Jul 2025 format-style variables and $(PI:fmt)
        assert_eq!(format_printf("%.3f", pi).unwrap(), "3.142");
        assert_eq!(format_printf("%10.4f", pi).unwrap(), "    3.1416");
        assert_eq!(format_printf("%-10.4f", pi).unwrap(), "3.1416    ");
        assert_eq!(format_printf("% .2g", pi).unwrap(), " 3.1");
        assert_eq!(format_printf("%08.3f", pi).unwrap(), "0003.142");
        assert_eq!(format_printf("%5.3F", pi).unwrap(), "3.142");
        assert_eq!(format_printf("%.0f", pi).unwrap(), "3");
        assert_eq!(format_printf("%f", pi).unwrap(), "3.141593");
        assert_eq!(format_printf("%10.3G", pi).unwrap(), "      3.14");
        assert_eq!(format_printf("%.3e", pi).unwrap(), "3.142e+00");
        assert_eq!(format_printf("%.17g", pi).unwrap(), "3.1415926535897931");
        assert_eq!(format_printf("%.25f", pi).unwrap(), "3.1415926535897931159979635");
        assert_eq!(format_printf("%.3f units", pi).unwrap(), "3.142 units");
        assert_eq!(format_printf("%.3f%%", pi).unwrap(), "3.142%");
        assert_eq!(format_printf("%.3f", -0.0).unwrap(), "-0.000");
        // C semantics of the other flags
        assert_eq!(format_printf("%+.2e", pi).unwrap(), "+3.14e+00");
        assert_eq!(format_printf("%#.3g", 1.0).unwrap(), "1.00");
        assert_eq!(format_printf("%#.0f", 1.0).unwrap(), "1.");
        assert_eq!(format_printf("%#.0e", 1.0).unwrap(), "1.e+00");
        assert_eq!(format_printf("%-+8.2f|", 2.0).unwrap(), "+2.00   |");
        assert_eq!(format_printf("%08.2e", -2.0).unwrap(), "-2.00e+00");
        assert_eq!(format_printf("%010.2e", -2.0).unwrap(), "-02.00e+00");
        assert_eq!(format_printf("%08.2f", f64::INFINITY).unwrap(), "     inf");
        assert_eq!(format_printf("%-6g|", f64::NAN).unwrap(), "nan   |");
        assert_eq!(format_printf("%E", -f64::INFINITY).unwrap(), "-INF");
        assert_eq!(format_printf("%d", 42.9).unwrap(), "42");
        assert_eq!(format_printf("%5d", -42.0).unwrap(), "  -42");
        assert_eq!(format_printf("%05d", -42.0).unwrap(), "-0042");
        assert_eq!(format_printf("%-5i|", 7.0).unwrap(), "7    |");
        assert_eq!(format_printf("%.3d", 7.0).unwrap(), "007");
        assert_eq!(format_printf("%.0d", 0.0).unwrap(), "");
        assert_eq!(format_printf("%lf", 0.5).unwrap(), "0.500000");
        assert_eq!(format_printf("step", 1.0).unwrap(), "step");
        assert!(format_printf("%.3f %.2f", pi).is_err());
        assert!(format_printf("%s", pi).is_err());
        assert!(format_printf("%", pi).is_err());
        // a multi-byte character where the conversion should be is named whole, never split
        let e = format_printf("%.700\u{20ac}00e", pi).unwrap_err();
        assert!(e.contains("`%.700\u{20ac}`"), "{e}");
    }

    #[test]
    fn widths_and_precisions_above_the_limit_are_refused() {
        assert_eq!(format_printf("%.4096f", 0.5).unwrap().len(), 4098);
        assert_eq!(format_printf("%4096.1f", 0.5).unwrap().len(), 4096);
        for f in ["%.4097f", "%.70000f", "%.70000g", "%.70000e", "%.70000d", "%.99999999999999999999999f"] {
            let e = format_printf(f, 1.5).unwrap_err();
            assert!(e.contains("precision") && e.contains("at most 4096"), "{f}: {e}");
        }
        for f in ["%4097f", "%99999999999.2f", "%99999999999999999999999g"] {
            let e = format_printf(f, 1.5).unwrap_err();
            assert!(e.contains("width") && e.contains("at most 4096"), "{f}: {e}");
        }
        // a hand-made conversion past the limit is clamped, never a panic
        let c = Conversion { precision: Some(70000), width: 1 << 40, conv: 'g', ..Conversion::default() };
        assert!(format_one(1.5, &c).len() <= MAX_FIELD + 8);
    }

    #[test]
    fn lammps_format_checks() {
        for f in ["%.3f", "%10.4f", "%-10.4f", "% .2g", "%08.3f", "%5.3F", "%f", "%5f", "%.f", "%-.3e", "% -5.2f"] {
            assert!(is_format_style_spec(f), "{f}");
        }
        for f in ["%+.3e", "%#.3g", "x=%.3f", "%.3f units", "%d", "%.3f%%", "%0-5.2f", "%--5.2f", "%5.2"] {
            assert!(!is_format_style_spec(f), "{f}");
        }
        for f in ["%.3f", "%10.4f", "% .2g", "%08.3f", "%.3f units", "%.3f%%", "%.3fx", "%.3e"] {
            assert!(is_immediate_format_spec(f), "{f}");
        }
        for f in ["%-10.4f", "%+.3e", "%#.3g", "%d", "%f", "%5f", "%.f", "%5.2"] {
            assert!(!is_immediate_format_spec(f), "{f}");
        }
    }

    /// `%.15g` and `%.20g` printed by glibc `printf` (identical to Python's `'%.15g' % x` except
    /// that Python drops the sign of a NaN): special values, random bit patterns, short
    /// decimals, and powers of ten with their neighbours. Checked during development over
    /// 82,551 doubles and 17 conversions (1.4 million strings) with no difference.
    #[test]
    fn g_matches_glibc() {
        let cases: &[(u64, &str, &str)] = &[
        (0x0000000000000000, "0", "0"),
        (0x8000000000000000, "-0", "-0"),
        (0x3ff0000000000000, "1", "1"),
        (0xbff0000000000000, "-1", "-1"),
        (0x3fe0000000000000, "0.5", "0.5"),
        (0x3fc0000000000000, "0.125", "0.125"),
        (0x3fd8000000000000, "0.375", "0.375"),
        (0x4004000000000000, "2.5", "2.5"),
        (0x430c6bf526340000, "1e+15", "1000000000000000"),
        (0x4341c37937e08000, "1e+16", "10000000000000000"),
        (0x444b1ae4d6e2ef50, "1e+21", "1e+21"),
        (0x3ee4f8b588e368f1, "1e-05", "1.0000000000000000818e-05"),
        (0x3f1a36e2eb1c432d, "0.0001", "0.00010000000000000000479"),
        (0x3f1a36d1bd105b06, "9.9999e-05", "9.9999000000000002599e-05"),
        (0x3f1a36e2eb1c432d, "0.0001", "0.00010000000000000000479"),
        (0x437b69b4ba630f35, "1.23456789012346e+17", "123456789012345680"),
        (0x0000000000000001, "4.94065645841247e-324", "4.9406564584124654418e-324"),
        (0x0010000000000000, "2.2250738585072e-308", "2.2250738585072013831e-308"),
        (0x7fefffffffffffff, "1.79769313486232e+308", "1.7976931348623157081e+308"),
        (0x7ff0000000000000, "inf", "inf"),
        (0xfff0000000000000, "-inf", "-inf"),
        (0x7ff8000000000000, "nan", "nan"),
        (0xfff8000000000000, "-nan", "-nan"),
        (0x412e847f00000000, "999999.5", "999999.5"),
        (0x416312cff0000000, "9999999.5", "9999999.5"),
        (0x3f1a36e20f35445e, "9.999995e-05", "9.9999950000000001294e-05"),
        (0x54b249ad2594c37d, "1e+100", "1.0000000000000000159e+100"),
        (0x4008000000000000, "3", "3"),
        (0x4024000000000000, "10", "10"),
        (0x4059000000000000, "100", "100"),
        (0x412e848000000000, "1000000", "1000000"),
        (0x416312d000000000, "10000000", "10000000"),
        (0x3fb999999999999a, "0.1", "0.10000000000000000555"),
        (0x3fc999999999999a, "0.2", "0.2000000000000000111"),
        (0x3fd3333333333333, "0.3", "0.2999999999999999889"),
        (0x8249c31859027b10, "-1.23099246500661e-297", "-1.2309924650066054449e-297"),
        (0x21404cd62d5c22ef, "1.59346879485275e-148", "1.5934687948527530626e-148"),
        (0x6009b2d3dd82f4d7, "4.30701449454192e+154", "4.3070144945419215255e+154"),
        (0x9ac0a0f76ae94231, "-8.01480318233139e-180", "-8.0148031823313944064e-180"),
        (0xf7a837d0dee795a4, "-2.4988775899359e+268", "-2.4988775899359024557e+268"),
        (0xc1869e54340a569d, "-47434374.505048", "-47434374.505048014224"),
        (0x1ea655c0067597cd, "4.96452306990135e-161", "4.964523069901348946e-161"),
        (0xd1384bf1d92765b0, "-1.84376420874522e+83", "-1.8437642087452176398e+83"),
        (0x383f7916f0f44989, "9.24908527883378e-38", "9.249085278833783038e-38"),
        (0xe0db4dea6e8fd4c8, "-3.74877791265242e+158", "-3.7487779126524169623e+158"),
        (0xf18ab5d46c6f6905, "-8.69650796125038e+238", "-8.6965079612503750634e+238"),
        (0xc56e03004e3f5485, "-2.90255578609645e+26", "-2.90255578609645383e+26"),
        (0xba80b5c03e96726e, "-6.74910098136204e-27", "-6.7491009813620404397e-27"),
        (0x60c4036b686a7bae, "1.37387650863907e+158", "1.3738765086390692001e+158"),
        (0x528ef26d7513764f, "4.92500914773111e+89", "4.9250091477311080687e+89"),
        (0x7e6271ca9e02b98a, "6.17607446929774e+300", "6.1760744692977427862e+300"),
        (0x7c6f76c142a51128, "2.45300362534845e+291", "2.45300362534845031e+291"),
        (0xeb6f2c3f603aa60f, "-3.20260518681265e+209", "-3.2026051868126504562e+209"),
        (0x84076ba720292ea9, "-3.00407442711869e-289", "-3.0040744271186910065e-289"),
        (0x96d70eb89bc9ed8b, "-1.20491155898876e-198", "-1.204911558988757801e-198"),
        (0x5b8e3f5df72c735e, "1.07348995789043e+133", "1.0734899578904316902e+133"),
        (0x51ca34b1f707d1c5, "1.01818542383865e+86", "1.0181854238386538114e+86"),
        (0xcc5bfb09a0685cd1, "-7.02548683967731e+59", "-7.0254868396773060282e+59"),
        (0x29cd469aaeeb9ad9, "2.49310342459302e-107", "2.4931034245930158695e-107"),
        (0xc9e3bc09415f0c36, "-9.01313367985952e+47", "-9.0131336798595204981e+47"),
        (0xdabd127a17bb476c, "-1.25949281116169e+129", "-1.2594928111616863109e+129"),
        (0x2eadab6b534fc0d7, "7.63630038163414e-84", "7.6363003816341394171e-84"),
        (0x57da4163b9b63391, "1.61643208493308e+115", "1.6164320849330785942e+115"),
        (0x53baba3bc2e45c1b, "2.23006010895787e+95", "2.2300601089578691217e+95"),
        (0xb7e93901054f213c, "-2.31633658150075e-39", "-2.3163365815007461372e-39"),
        (0xcaa381635f6b6990, "-3.64892249660362e+51", "-3.6489224966036196716e+51"),
        (0x1b6923be3bebca50, "1.24077001182252e-176", "1.2407700118225200412e-176"),
        (0x730256e0371b3f49, "1.00177599575733e+246", "1.0017759957573272184e+246"),
        (0x4cf952d76e66fdcf, "6.51095292926041e+62", "6.5109529292604094802e+62"),
        (0x672c47beedc932ff, "9.84397839647001e+188", "9.8439783964700130805e+188"),
        (0xceaa7c137ac79f19, "-9.13952449227457e+70", "-9.1395244922745690836e+70"),
        (0xded402209b935422, "-6.3959974815947e+148", "-6.3959974815947024239e+148"),
        (0x8fecb9722198feb5, "-5.78181622668746e-232", "-5.7818162266874598675e-232"),
        (0x8b014ebf77cce6ca, "-1.15268533284971e-255", "-1.1526853328497052156e-255"),
        (0x98267dd124c73e40, "-2.4648509881092e-192", "-2.464850988109195104e-192"),
        (0xbf54e876eec135b7, "-0.001276127", "-0.0012761269999999999471"),
        (0xbffd21e4f765fd8b, "-1.820775", "-1.8207750000000000323"),
        (0x3f44d944c4190ddd, "0.000636252", "0.0006362520000000000198"),
        (0x3f22a366641c9104, "0.0001421988", "0.00014219880000000001147"),
        (0x40f9651333333333, "104017.2", "104017.19999999999709"),
        (0xbf2509f7568c745a, "-0.0001605143", "-0.00016051429999999999561"),
        (0xbfbeec6a21060a05, "-0.1207949", "-0.12079489999999999672"),
        (0xbffe97efe0ce0b91, "-1.912094", "-1.9120939999999999603"),
        (0xc0651e985f06f694, "-168.9561", "-168.95609999999999218"),
        (0xbf89c71bb2e3ed7b, "-0.0125868", "-0.012586800000000000418"),
        (0xbec089871d2b3723, "-1.97139e-06", "-1.9713900000000000259e-06"),
        (0xbf394b4465cf5684, "-0.000385956", "-0.00038595600000000001607"),
        (0x40c27c4000000000, "9464.5", "9464.5"),
        (0x4107d2e0cccccccd, "195164.1", "195164.10000000000582"),
        (0x3fb866d018b1a7ad, "0.0953188", "0.095318799999999995198"),
        (0xbf12a2efd9973591, "-7.10925e-05", "-7.1092499999999997384e-05"),
        (0x40e98beccccccccd, "52319.4", "52319.400000000001455"),
        (0x3f5fbdabd8c7930d, "0.001937311", "0.0019373109999999999376"),
        (0xbf208248081b4646, "-0.000125953", "-0.00012595299999999999161"),
        (0xc0d0beeae147ae14, "-17147.67", "-17147.669999999998254"),
        (0xc134dd1d00000000, "-1367325", "-1367325"),
        (0x3f8887c505d907ef, "0.01197771", "0.011977710000000000787"),
        (0x3f5f477ae03d645c, "0.001909132", "0.0019091320000000000165"),
        (0xc0cbcec147ae147b, "-14237.51", "-14237.510000000000218"),
        (0x4005d4b9cb6848bf, "2.72887", "2.7288700000000001289"),
        (0xc029c182a9930be1, "-12.87795", "-12.87795000000000023"),
        (0xc0ec15e666666666, "-57519.2", "-57519.19999999999709"),
        (0x3ee5255af5456f26, "1.008316e-05", "1.0083159999999999188e-05"),
        (0xc00f7e5c91d14e3c, "-3.9367", "-3.9367000000000000881"),
        (0xbee14a3b73afb64d, "-8.2445e-06", "-8.2445000000000004311e-06"),
        (0xbfc3183ebb26b21b, "-0.1491774", "-0.14917739999999998779"),
        (0x3f94671892f3e311, "0.01992453", "0.019924529999999999325"),
        (0x3f11011c44353765, "6.48664e-05", "6.4866399999999999515e-05"),
        (0x40967e6560418937, "1439.599", "1439.5989999999999327"),
        (0x3f2142a6206e3d28, "0.000131686", "0.00013168599999999999924"),
        (0x40d1085147ae147b, "17441.27", "17441.270000000000437"),
        (0xbf91b6babca9e9f4, "-0.01729862", "-0.017298620000000000663"),
        (0xbef0f9bb2b0375c1, "-1.618911e-05", "-1.6189110000000001265e-05"),
        (0x4067bb1a9fbe76c9, "189.847", "189.84700000000000841"),
        (0xc0f7521ccccccccd, "-95521.8", "-95521.80000000000291"),
        (0x4543e54a474cd656, "4.8104765388067e+25", "4.8104765388066994717e+25"),
        (0x3ec31215ee052a36, "2.27339829464892e-06", "2.2733982946489230258e-06"),
        (0x44af9fa13445c7c5, "7.4669004631371e+22", "7.4669004631371010802e+22"),
        (0x4536faa427b5fc26, "2.77799877797377e+25", "2.7779987779737719916e+25"),
        (0x435f89902ba60200, "3.55079063145042e+16", "35507906314504192"),
        (0x41e7ab527cf090c8, "3176829927.51767", "3176829927.5176734924"),
        (0x3f21c7d1b4f8e4a0, "0.000135654782285309", "0.00013565478228530925692"),
        (0x42a72a6ad2a191a0, "12735474127048.8", "12735474127048.8125"),
        (0x418d938c7346e533, "62026126.4096169", "62026126.409616850317"),
        (0x436caa2af9f99c00, "6.45472072570552e+16", "64547207257055232"),
        (0x40e1f8bfcb99eac4, "36805.9936036668", "36805.993603666807758"),
        (0x3fc14a84cfed61b9, "0.135086633231152", "0.1350866332311520257"),
        (0x41f32585ffbc8398, "5139619835.78213", "5139619835.7821273804"),
        (0x456b24a703cfb394, "2.62512665630993e+26", "2.6251266563099323975e+26"),
        (0x452b94f8e6680300, "1.66722493820567e+25", "1.6672249382056650007e+25"),
        (0x442d8abe11b48094, "2.72476512913668e+20", "2.7247651291366752256e+20"),
        (0x40dfa230d4362526, "32392.7629523623", "32392.76295236232545"),
        (0x41425b8461250574, "2406152.7589423", "2406152.7589423004538"),
        (0x40c553e53ba2ecf7, "10919.7908824594", "10919.790882459359636"),
        (0x3da23be2fb909cf4, "8.29183237818339e-12", "8.2918323781833916404e-12"),
        (0x05cd0b15a491eb84, "1e-280", "9.9999999999999995736e-281"),
        (0x0de5566ffafb1eaf, "1e-241", "9.9999999999999980287e-242"),
        (0x740bef1c9657a685, "1e+251", "9.999999999999999211e+250"),
        (0x774f03542dfb8370, "5e+266", "4.9999999999999998672e+266"),
        (0x4023ffffffffffff, "10", "9.9999999999999982236"),
        (0x45c027e72f1f1280, "1e+28", "9.9999999999999973841e+27"),
        (0x47d2ced32a16a1b2, "1e+38", "1.0000000000000001664e+38"),
        (0x7bba44df832b8d47, "1e+288", "1.0000000000000001429e+288"),
        (0x66f6fb97ea6a9d39, "1e+188", "1.0000000000000001777e+188"),
        (0x78c27c35704a5e67, "5e+273", "4.9999999999999996069e+273"),
        (0x5e7405552d60dbd6, "1e+147", "9.99999999999999978e+146"),
        (0x0c06e93f5da2824b, "1e-250", "9.9999999999999989893e-251"),
        (0x115d9ca79d89462a, "5e-225", "5.0000000000000000944e-225"),
        (0x36cc8b8218854566, "1e-44", "9.9999999999999982853e-45"),
        (0x62315d847ad00086, "1e+165", "9.999999999999996949e+164"),
        (0x0b32c4cf8ea6b6ed, "1e-254", "1.0000000000000001015e-254"),
        (0x0a5ec033b40fea93, "1e-258", "9.9999999999999995422e-259"),
        (0x3f50624dd2f1a9fc, "0.001", "0.0010000000000000000208"),
        (0x7857a93a2954f3b7, "5e+271", "4.9999999999999995769e+271"),
        (0x5c2b843422e3a84c, "1e+136", "9.9999999999999992955e+135"),
        (0x39e95a5efea6b346, "1e-29", "9.9999999999999980308e-30"),
        (0x4f81afd6ec0e1411, "1e+75", "9.9999999999999992654e+74"),
        (0x4733426172c74d81, "1e+35", "9.9999999999999978417e+34"),
        (0x0244ed8b04671da5, "1e-297", "1.0000000000000000396e-297"),
        (0x5fa317e5ef3ab327, "5e+152", "4.9999999999999999987e+152"),
        ];
        for &(bits, g15, g20) in cases {
            let x = f64::from_bits(bits);
            assert_eq!(format_g(x, 15), g15, "{bits:016x}");
            assert_eq!(format_g(x, 20), g20, "{bits:016x}");
        }
    }

    #[test]
    fn shortest_as_fmt() {
        for (x, s) in [(1.4906985857069832, "1.4906985857069832"), (1.0, "1"), (1e-5, "1e-05"), (-2.5e-7, "-2.5e-07"), (1e16, "1e+16"), (123.0, "123"), (1e-4, "0.0001"), (0.0, "0"), (f64::NAN, "nan"), (1.5e300, "1.5e+300")] {
            assert_eq!(super::shortest(x), s);
        }
    }
}
