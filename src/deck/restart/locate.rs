//! Where a field of a restart file is, for located errors: the byte range of the value at a
//! path such as `atoms.type[2]` or `box.current`, found by scanning the JSON text (serde keeps
//! no positions). The scanner only steps over valid JSON, which the file is when its fields are
//! checked; on anything else it stops and the deepest member found so far is the place.

/// The byte range of the value at `path` (members by name, elements by `[k]`); where a later
/// step of the path is missing, the range of the deepest value found. None if not even the
/// first step is in the file (the path is no field of it).
pub fn locate(text: &str, path: &str) -> Option<(usize, usize)> {
    let b = text.as_bytes();
    let mut at = skip_ws(b, 0);
    let mut found = None;
    for step in steps(path) {
        let next = match step {
            Step::Member(name) => member(b, at, name),
            Step::Element(k) => element(b, at, k),
        };
        let Some(start) = next else { break };
        at = start;
        found = Some((at, skip_value(b, at).unwrap_or(b.len())));
    }
    found
}

/// The byte offset of line `line`, column `column` (both from 1, as serde_json counts them).
pub fn offset_of(text: &str, line: usize, column: usize) -> usize {
    let start: usize = text.split_inclusive('\n').take(line.saturating_sub(1)).map(str::len).sum();
    (start + column.saturating_sub(1)).min(text.len())
}

/// The field path a check message starts with (`atoms.type[5] (atom 6) is 0...` ->
/// `atoms.type[5]`): the messages of `Restart::check` all name their field first.
pub fn leading_path(message: &str) -> &str {
    let end = message.find(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '[' | ']'))).unwrap_or(message.len());
    &message[..end]
}

enum Step<'a> {
    Member(&'a str),
    Element(usize),
}

fn steps(path: &str) -> Vec<Step<'_>> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (name, rest) = part.split_once('[').map_or((part, ""), |(n, r)| (n, r));
        if !name.is_empty() {
            out.push(Step::Member(name));
        }
        for index in rest.split('[') {
            if let Ok(k) = index.trim_end_matches(']').parse() {
                out.push(Step::Element(k));
            }
        }
    }
    out
}

fn skip_ws(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && b[i].is_ascii_whitespace() {
        i += 1;
    }
    i
}

/// The end of the string starting at `i` (a `"`).
fn skip_string(b: &[u8], mut i: usize) -> Option<usize> {
    i += 1;
    while i < b.len() {
        match b[i] {
            b'\\' => i += 2,
            b'"' => return Some(i + 1),
            _ => i += 1,
        }
    }
    None
}

/// The end of the value starting at `i`.
fn skip_value(b: &[u8], i: usize) -> Option<usize> {
    match *b.get(i)? {
        b'"' => skip_string(b, i),
        b'{' | b'[' => {
            let mut depth = 0usize;
            let mut k = i;
            while k < b.len() {
                match b[k] {
                    b'"' => {
                        k = skip_string(b, k)?;
                        continue;
                    }
                    b'{' | b'[' => depth += 1,
                    b'}' | b']' => {
                        depth -= 1;
                        if depth == 0 {
                            return Some(k + 1);
                        }
                    }
                    _ => {}
                }
                k += 1;
            }
            None
        }
        _ => {
            let mut k = i;
            while k < b.len() && !matches!(b[k], b',' | b']' | b'}') && !b[k].is_ascii_whitespace() {
                k += 1;
            }
            Some(k)
        }
    }
}

/// The start of member `name`'s value in the object starting at `i`.
fn member(b: &[u8], i: usize, name: &str) -> Option<usize> {
    if b.get(i) != Some(&b'{') {
        return None;
    }
    let mut k = skip_ws(b, i + 1);
    while b.get(k) == Some(&b'"') {
        let key_end = skip_string(b, k)?;
        let key = &b[k + 1..key_end - 1];
        k = skip_ws(b, key_end);
        if b.get(k) != Some(&b':') {
            return None;
        }
        let value = skip_ws(b, k + 1);
        if key == name.as_bytes() {
            return Some(value);
        }
        k = skip_ws(b, skip_value(b, value)?);
        if b.get(k) != Some(&b',') {
            return None;
        }
        k = skip_ws(b, k + 1);
    }
    None
}

/// The start of element `index` of the array starting at `i`.
fn element(b: &[u8], i: usize, index: usize) -> Option<usize> {
    if b.get(i) != Some(&b'[') {
        return None;
    }
    let mut k = skip_ws(b, i + 1);
    for _ in 0..index {
        k = skip_ws(b, skip_value(b, k)?);
        if b.get(k) != Some(&b',') {
            return None;
        }
        k = skip_ws(b, k + 1);
    }
    (k < b.len() && b[k] != b']').then_some(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_members_elements_and_the_deepest_existing_step() {
        let text = "{\n  \"a\": {\"type\": [1,2, 30], \"s\": \"x]\\\"}\"},\n  \"b\": [[1,2],\n    [3, 4]]\n}";
        let at = |path: &str| {
            let (lo, hi) = locate(text, path).unwrap();
            &text[lo..hi]
        };
        assert_eq!(at("a.type[2]"), "30");
        assert_eq!(at("a.type"), "[1,2, 30]");
        assert_eq!(at("a.s"), "\"x]\\\"}\"");
        assert_eq!(at("b[1][0]"), "3");
        assert_eq!(at("b[1]"), "[3, 4]");
        // missing steps: the deepest value that exists
        assert_eq!(at("a.type[7]"), "[1,2, 30]");
        assert_eq!(at("a.rho"), &text[text.find("{\"type\"").unwrap()..text.find("},").unwrap() + 1]);
        assert_eq!(locate(text, "c.type"), None);
        assert_eq!(leading_path("atoms.type[5] (atom 6) is 0"), "atoms.type[5]");
        assert_eq!(leading_path("box.current: lo[0] = 1"), "box.current");
        assert_eq!(offset_of(text, 2, 3), text.find("\"a\"").unwrap());
    }
}
