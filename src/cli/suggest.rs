//! Did-you-mean suggestions: the known name closest to a mistyped one (subcommands, `new`'s
//! templates).

/// The name in `names` closest to `word` when it is close enough to be a likely typo (at most
/// 2 edits, or a third of the name's length for long names).
pub fn closest<'a>(word: &str, names: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let (distance, best) = names
        .into_iter()
        .map(|n| (edit_distance(word, n), n))
        .min()?;
    (distance <= 2.max(best.len() / 3)).then_some(best)
}

/// Levenshtein distance between two short words (insertions, deletions, substitutions).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::{closest, edit_distance};

    #[test]
    fn edit_distance_of_hand_checked_pairs() {
        assert_eq!(edit_distance("inpsect", "inspect"), 2);
        assert_eq!(edit_distance("resme", "resume"), 1);
        assert_eq!(edit_distance("", "plot"), 4);
        assert_eq!(edit_distance("bench", "bench"), 0);
    }

    #[test]
    fn only_a_close_name_is_suggested() {
        let names = ["foraging", "t-maze", "eye-arena"];
        assert_eq!(closest("foragin", names), Some("foraging"));
        assert_eq!(closest("t-mzae", names), Some("t-maze"));
        assert_eq!(closest("zzzzzz", names), None);
    }
}
