//! "Did you mean ...?" suggestions for misspelled names.

/// The closest candidate to `word` if it is close enough to be a plausible typo.
pub fn did_you_mean<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let mut best: Option<(&str, f64)> = None;
    for c in candidates {
        let score = strsim::jaro_winkler(word, c);
        let close = strsim::levenshtein(word, c) <= (word.len().max(c.len()) / 3).max(1);
        if (score >= 0.85 || close) && best.map(|(_, s)| score > s).unwrap_or(true) {
            best = Some((c, score));
        }
    }
    best.map(|(c, _)| c)
}

/// `help:` text for a suggestion, or None.
pub fn did_you_mean_help<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<String> {
    did_you_mean(word, candidates).map(|c| format!("did you mean `{c}`?"))
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn suggests_close_names() {
        assert_eq!(did_you_mean("pair_stlye", ["pair_style", "pair_coeff", "units"]), Some("pair_style"));
        assert_eq!(did_you_mean("timestpe", ["timestep", "thermo"]), Some("timestep"));
        assert_eq!(did_you_mean("xyzzy", ["timestep", "thermo"]), None);
    }
}
