//! PLACEHOLDER (parser-script helper): minimal C printf formatting so the interpreter compiles
//! and its tests run. The parser-expr helper's numfmt.rs replaces this file.

/// C printf `%.{precision}g`.
pub fn format_g(x: f64, precision: usize) -> String {
    fmt_g(x, precision, false, false)
}

fn fmt_g(x: f64, precision: usize, alt: bool, upper: bool) -> String {
    if !x.is_finite() {
        return special(x, upper);
    }
    let p = precision.max(1);
    let e_form = format!("{:.*e}", p - 1, x);
    let exp: i32 = e_form.split('e').nth(1).and_then(|s| s.parse().ok()).unwrap_or(0);
    let mut s = if exp < -4 || exp >= p as i32 {
        c_exponent(&e_form, upper)
    } else {
        format!("{:.*}", (p as i32 - 1 - exp).max(0) as usize, x)
    };
    if !alt {
        s = strip_zeros(&s);
    }
    s
}

fn special(x: f64, upper: bool) -> String {
    let s = if x.is_nan() { "nan" } else if x > 0.0 { "inf" } else { "-inf" };
    if upper { s.to_uppercase() } else { s.to_string() }
}

/// Rust `1.5e3` -> C `1.5e+03`.
fn c_exponent(rust: &str, upper: bool) -> String {
    let (m, e) = rust.split_once('e').unwrap_or((rust, "0"));
    let e: i32 = e.parse().unwrap_or(0);
    let sign = if e < 0 { '-' } else { '+' };
    format!("{m}{}{sign}{:02}", if upper { 'E' } else { 'e' }, e.abs())
}

fn strip_zeros(s: &str) -> String {
    let (mant, exp) = match s.find(['e', 'E']) {
        Some(k) => (&s[..k], &s[k..]),
        None => (s, ""),
    };
    if !mant.contains('.') {
        return s.to_string();
    }
    let mant = mant.trim_end_matches('0').trim_end_matches('.');
    format!("{mant}{exp}")
}

/// One C conversion (`%[flags][width][.precision]conv`) applied to `x`.
pub fn format_printf(fmt: &str, x: f64) -> Result<String, String> {
    let b = fmt.as_bytes();
    if b.first() != Some(&b'%') {
        return Err(format!("format `{fmt}` does not start with %"));
    }
    let mut i = 1;
    let (mut left, mut plus, mut space, mut zero, mut alt) = (false, false, false, false, false);
    while i < b.len() && b"-+ 0#".contains(&b[i]) {
        match b[i] {
            b'-' => left = true,
            b'+' => plus = true,
            b' ' => space = true,
            b'0' => zero = true,
            _ => alt = true,
        }
        i += 1;
    }
    let w0 = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let width: usize = fmt[w0..i].parse().unwrap_or(0);
    let mut prec: Option<usize> = None;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        let p0 = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        prec = Some(fmt[p0..i].parse().unwrap_or(0));
    }
    if i + 1 != b.len() {
        return Err(format!("format `{fmt}` must be a single conversion"));
    }
    let conv = b[i] as char;
    let mut body = match conv {
        'f' | 'F' => if x.is_finite() { format!("{:.*}", prec.unwrap_or(6), x) } else { special(x, conv == 'F') },
        'e' | 'E' => if x.is_finite() { c_exponent(&format!("{:.*e}", prec.unwrap_or(6), x), conv == 'E') } else { special(x, conv == 'E') },
        'g' | 'G' => fmt_g(x, prec.unwrap_or(6), alt, conv == 'G'),
        'd' | 'i' => format!("{}", x as i64),
        _ => return Err(format!("unsupported conversion `%{conv}`")),
    };
    if !body.starts_with('-') {
        if plus {
            body.insert(0, '+');
        } else if space {
            body.insert(0, ' ');
        }
    }
    if body.len() < width {
        let pad = width - body.len();
        if left {
            body.push_str(&" ".repeat(pad));
        } else if zero && x.is_finite() {
            let k = if body.starts_with(['-', '+', ' ']) { 1 } else { 0 };
            body.insert_str(k, &"0".repeat(pad));
        } else {
            body.insert_str(0, &" ".repeat(pad));
        }
    }
    Ok(body)
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn c_like() {
        assert_eq!(format_g(1.0 / 3.0, 20), "0.33333333333333331483");
        assert_eq!(format_g(2.0, 20), "2");
        assert_eq!(format_g(1e-5, 6), "1e-05");
        assert_eq!(format_g(1.5e300 * 1e300, 15), "inf");
        assert_eq!(format_printf("%10.4e", 2.0 / 3.0).unwrap(), "6.6667e-01");
        assert_eq!(format_printf("%.3f", 1.0 / 3.0).unwrap(), "0.333");
    }
}
