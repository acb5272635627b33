//! A table laid out as the FST Editor shows it, for `linc fst list` and for
//! listings next to the compiled code.

use super::Table;

/// The table in aligned columns; with `offsets` (step i's instruction
/// offset at `offsets[i]`) an IP column comes first.
pub fn listing(table: &Table, offsets: Option<&[u32]>) -> String {
    let mut lines: Vec<Vec<String>> = Vec::with_capacity(table.rows.len() + 1);
    let mut head: Vec<String> =
        ["STEP", "LABEL", "CMD", "ARGUMENT1", "ARGUMENT2", "COMMENT"].map(String::from).to_vec();
    if offsets.is_some() {
        head.insert(0, "IP".to_string());
    }
    lines.push(head);
    for (i, r) in table.rows.iter().enumerate() {
        let cell = |c: &Option<super::Cell>| c.as_ref().map(|c| c.text.clone()).unwrap_or_default();
        let mut line = vec![r.step.to_string(), cell(&r.label), r.cmd.text.clone(), cell(&r.arg1), cell(&r.arg2)];
        line.push(r.comment.clone());
        if let Some(offsets) = offsets {
            line.insert(0, offsets.get(i).map(u32::to_string).unwrap_or_default());
        }
        lines.push(line);
    }
    let columns = lines.first().map_or(0, Vec::len);
    let widths: Vec<usize> = (0..columns)
        .map(|c| lines.iter().map(|l| l.get(c).map_or(0, |s| s.chars().count())).max().unwrap_or(0))
        .collect();
    let mut out = String::new();
    for line in &lines {
        let mut text = String::new();
        for (cell, width) in line.iter().zip(&widths) {
            text.push_str(cell);
            text.push_str(&" ".repeat(width - cell.chars().count() + 2));
        }
        out.push_str(text.trim_end());
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fst::reader::read;

    const B4: &str = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n0,,GO,PMPOFF,,\n1,PUMPON,DO,DOU 4-1,1,\n2,PMPOFF,DO,DOU 4-2,0,pump off\n";

    #[test]
    fn lists_table_b4_aligned() {
        let (t, _) = read(B4);
        let expected = "\
STEP  LABEL   CMD  ARGUMENT1  ARGUMENT2  COMMENT
0             GO   PMPOFF
1     PUMPON  DO   DOU 4-1    1
2     PMPOFF  DO   DOU 4-2    0          pump off
";
        assert_eq!(listing(&t, None), expected);
    }

    #[test]
    fn lists_instruction_offsets_first() {
        let (t, _) = read(B4);
        let expected = "\
IP  STEP  LABEL   CMD  ARGUMENT1  ARGUMENT2  COMMENT
0   0             GO   PMPOFF
2   1     PUMPON  DO   DOU 4-1    1
17  2     PMPOFF  DO   DOU 4-2    0          pump off
";
        assert_eq!(listing(&t, Some(&[0, 2, 17])), expected);
    }
}
