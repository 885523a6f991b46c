//! "Did you mean": the closest of a list of names to a misspelt one, for library names and the
//! keywords of the input grammars.

/// The name closest to `arg` (case-insensitive edit distance), when it is close: at most a
/// third of the name's length, and at least one edit for names of three letters.
pub(crate) fn did_you_mean<'a>(arg: &str, names: &[&'a str]) -> Option<&'a str> {
    let a: Vec<char> = arg.to_lowercase().chars().collect();
    let distance = |b: &str| {
        let b: Vec<char> = b.to_lowercase().chars().collect();
        // Levenshtein distance, one row at a time.
        let mut row: Vec<usize> = (0..=b.len()).collect();
        for (i, ca) in a.iter().enumerate() {
            let mut prev = row[0];
            row[0] = i + 1;
            for (j, cb) in b.iter().enumerate() {
                let cur = row[j + 1];
                row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
                prev = cur;
            }
        }
        row[b.len()]
    };
    names
        .iter()
        .map(|n| (distance(n), *n))
        .min()
        .filter(|(d, n)| *d <= (n.chars().count() / 3).max(1))
        .map(|(_, n)| n)
}
