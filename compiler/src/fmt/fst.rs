//! The layout of an FST table (`.csv`): the canonical header, six cells a
//! row, cells trimmed, quoted only where RFC 4180 needs it, `,` between
//! cells and one line break a row.

const HEADER: [&str; 6] = ["STEP", "LABEL", "CMD", "ARGUMENT1", "ARGUMENT2", "COMMENT"];

pub(crate) fn format(src: &str) -> String {
    let body = src.strip_prefix(crate::diag::files::BOM).unwrap_or(src);
    let delim = crate::fst::reader::delimiter(body);
    let mut reader =
        csv::ReaderBuilder::new().has_headers(false).flexible(true).delimiter(delim).from_reader(body.as_bytes());
    let mut writer =
        csv::WriterBuilder::new().flexible(true).terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
    let _ = writer.write_record(HEADER);
    for record in reader.records().skip(1).flatten() {
        let mut cells: Vec<&str> = record.iter().map(str::trim).collect();
        if cells.len() < HEADER.len() {
            cells.resize(HEADER.len(), "");
        }
        let _ = writer.write_record(&cells);
    }
    let bytes = writer.into_inner().unwrap_or_default();
    String::from_utf8(bytes).unwrap_or_default()
}
