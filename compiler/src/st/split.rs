//! Parsing the actions of one long file on two threads at once (ADR 0024).
//!
//! The text is cut into parts of about [`PART`] bytes, each starting at an
//! `ACTION` header at the start of a line, and two threads parse every other
//! part while the calling thread hands the items to the sink in order. A
//! part is read as a file of its own, which gives what the parse of the
//! whole file gives there only when the part before it ended cleanly: read
//! without any error (lexical, syntax, recovered or too deep), up to the
//! header where the next part starts, which it did not read, and accepted
//! there as a whole file. Then the parser of the whole file stands between
//! two actions at that header, with no errors counted, exactly as a parser
//! that starts there. A header inside a comment, a part with an error or an
//! action left open all make the part unclean; the rest of the file, from
//! that part's start, is then parsed as before, on one thread.
//!
//! Items reduced before a part's parser met its end are the whole file's
//! (the same parser read the same tokens), so they go to the sink as they
//! come; those reduced at its end (the last action, whose reduction waits
//! for the next token) are held until the part is known to be clean. When
//! it is not, the parse of the rest skips the items already handed over.

use crate::st::lexer::{Spanned, Tok};
use crate::st::parse_support::{Item, Parsed};
use crate::st::parser::{self, FileItems, ParseErrors, Part, BATCH};
use std::cell::Cell;
use std::sync::mpsc::{channel, sync_channel, Receiver, Sender, SyncSender};

/// A sink that gives an item back when it is done with it, so that the
/// thread that built the tree frees it: mimalloc frees a block allocated on
/// another thread at several times the cost of a local one.
pub type Giving<'a> = dyn FnMut(Item) -> Option<Item> + 'a;

/// The length a part has at least (but the last). Long enough that starting
/// a parse costs nothing beside it, short enough that the two threads keep
/// each other busy and that what waits for the sink stays small.
const PART: usize = 32 * 1024;

/// Messages waiting from the other thread: a part of [`PART`] bytes is
/// about one batch of actions and its end, so the other thread can parse
/// the parts up to the next one of the calling thread's while that thread
/// parses its own.
const QUEUE: usize = 8;

/// The calling thread parses this many parts in every so many ([`mine`]).
/// Once the trees the other thread parsed went back to it to be freed,
/// one in four left the other thread the longer (on the 1.25 MB file,
/// 180M instructions beside 163M); two in seven evens them.
const SHARE: (usize, usize) = (3, 10);

/// Where the parts start: 0, then the first `ACTION` header at the start of
/// a line at least [`PART`] bytes after the previous start. A header found
/// here may not be one (inside a comment, say); the parse finds that out.
pub(crate) fn part_starts(src: &str) -> Vec<usize> {
    let mut starts = vec![0];
    let mut from = PART;
    while let Some(at) = src.get(from..).and_then(|rest| rest.find("\nACTION")) {
        let start = from + at + 1;
        let after = src.as_bytes().get(start + "ACTION".len());
        if matches!(after, Some(b' ' | b'\t' | b'\r' | b'\n')) {
            starts.push(start);
            from = start + PART;
        } else {
            from = start;
        }
    }
    starts
}

/// What a parsing thread sends for a part: its items as they come, then how
/// it ended.
enum Msg {
    Items(Vec<Item>),
    End(End),
}

enum End {
    /// A part that ended cleanly at the next part's header, with the items
    /// reduced there.
    Clean(Vec<Item>),
    /// A part that did not: the rest of the file is parsed again from its
    /// start.
    Unclean,
    /// The last part: what the parse of the whole file gives.
    Last(Option<Parsed>, ParseErrors),
}

/// [`parser::parse_actions`] of a long text, on two threads while the
/// calling thread runs the sink. The sink sees the same items in the same
/// order and the result is the same; only the time differs.
///
/// The sink gives back the items it does not keep: those the other thread
/// parsed go back to it to be freed.
pub fn parse_actions_split_giving(src: &str, sink: &mut Giving) -> (bool, ParseErrors) {
    let starts = part_starts(src);
    let mut file = FileItems::default();
    let mut sink = |item: Item| {
        file.see(&item);
        sink(item)
    };
    let outcome = if starts.len() < 2 { Outcome::Rest(0, 0) } else { parse_parts(src, &starts, &mut sink) };
    let (parsed, errors) = match outcome {
        Outcome::Done(parsed, errors) => (parsed, errors),
        Outcome::Rest(start, skip) => parser::parse_rest_pipelined(src, start, skip, &mut |item| drop(sink(item))),
    };
    file.finish(matches!(parsed, Some(Parsed::File)), errors)
}

/// How the parallel parse ended: with the whole file's result, or at an
/// unclean part, from whose start (and after how many of its items, already
/// handed over) the rest is to be parsed.
enum Outcome {
    Done(Option<Parsed>, ParseErrors),
    Rest(usize, usize),
}

/// Parses the parts on two threads, handing their items to `sink` in order:
/// the calling thread parses its [`SHARE`] of them besides running the sink
/// on them all, a second thread the rest.
///
/// The items of the other thread's parts that the sink gives back go back
/// to that thread, which frees them between parts and, once done parsing,
/// until the calling thread is done: the frees cost it less and move off
/// the calling thread, which has the checking to do besides.
fn parse_parts(src: &str, starts: &[usize], sink: &mut Giving) -> Outcome {
    let (tx, rx) = sync_channel(QUEUE);
    let (back_tx, back_rx) = channel();
    std::thread::scope(|scope| {
        let parser = scope.spawn(move || parse_theirs(src, starts, tx, back_rx));
        let outcome = take_parts(src, starts, rx, back_tx, sink);
        // The receiver is gone: the thread, if still parsing, stops at its
        // next send. A panic on it is resumed here.
        parser.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        outcome
    })
}

/// Whether the calling thread parses part `i` itself. It parses [`SHARE`]
/// of the parts, spread evenly, and checks them all; the other thread
/// parses the rest. Parsing a part takes about twice as long as checking
/// it, so each thread then has about as much to do.
fn mine(i: usize) -> bool {
    let (some, every) = SHARE;
    i * some % every < some
}

/// The part of the text from `starts[i]` up to the next start.
fn part(starts: &[usize], i: usize) -> Part {
    Part { start: starts[i], end: starts.get(i + 1).copied().unwrap_or(usize::MAX) }
}

/// Hands the parts' items to `sink` in order, parsing its own parts and
/// taking the others from the other thread, until the last part or an
/// unclean one.
fn take_parts(
    src: &str,
    starts: &[usize],
    theirs: Receiver<Msg>,
    back: Sender<Vec<Item>>,
    sink: &mut Giving,
) -> Outcome {
    for (i, &start) in starts.iter().enumerate() {
        let mut handed = 0;
        let end = if mine(i) {
            parse_part(src, part(starts, i), &mut |items| {
                handed += items.len();
                items.into_iter().for_each(|item| drop(sink(item)));
                true
            })
        } else {
            take_theirs(&theirs, &back, &mut handed, sink)
        };
        match end {
            Some(End::Clean(held)) if mine(i) => held.into_iter().for_each(|item| drop(sink(item))),
            Some(End::Clean(held)) => give_back(&back, held, sink),
            // A closed channel means the other thread panicked; joining it
            // says so.
            Some(End::Unclean) | None => return Outcome::Rest(start, handed),
            Some(End::Last(parsed, errors)) => return Outcome::Done(parsed, errors),
        }
    }
    Outcome::Done(None, ParseErrors::default())
}

/// Hands `sink` the items of the other thread's next part, counting them in
/// `handed`; its end, or `None` if the thread is gone.
fn take_theirs(theirs: &Receiver<Msg>, back: &Sender<Vec<Item>>, handed: &mut usize, sink: &mut Giving) -> Option<End> {
    loop {
        match theirs.recv().ok()? {
            Msg::Items(items) => {
                *handed += items.len();
                give_back(back, items, sink);
            }
            Msg::End(end) => return Some(end),
        }
    }
}

/// Hands the other thread's `items` to `sink`, sending what it gives back
/// to that thread to be freed (here, if that thread is gone).
fn give_back(back: &Sender<Vec<Item>>, items: Vec<Item>, sink: &mut Giving) {
    let given: Vec<Item> = items.into_iter().filter_map(&mut *sink).collect();
    if !given.is_empty() {
        let _ = back.send(given);
    }
}

/// Parses the parts the calling thread does not ([`mine`]) and sends each
/// one's items and end. Stops when the receiver is gone (an unclean part,
/// or a panic).
/// Frees what comes back from the calling thread between parts and, once
/// every part is parsed, until that thread is done.
fn parse_theirs(src: &str, starts: &[usize], tx: SyncSender<Msg>, back: Receiver<Vec<Item>>) {
    for i in (0..starts.len()).filter(|&i| !mine(i)) {
        let Some(end) = parse_part(src, part(starts, i), &mut |items| {
            back.try_iter().for_each(drop);
            tx.send(Msg::Items(items)).is_ok()
        }) else {
            return;
        };
        if tx.send(Msg::End(end)).is_err() {
            return;
        }
        back.try_iter().for_each(drop);
    }
    drop(tx);
    back.into_iter().for_each(drop);
}

/// Parses one part, handing the items reduced before its end to `emit` in
/// batches; `None` once `emit` says no more are wanted.
fn parse_part(src: &str, part: Part, emit: &mut dyn FnMut(Vec<Item>) -> bool) -> Option<End> {
    let cut: Cell<Option<Spanned>> = Cell::new(None);
    let (mut batch, mut held, mut open) = (Vec::with_capacity(BATCH), Vec::new(), true);
    let (parsed, errors) = parser::run_part(src, Tok::StartFile, part, &cut, &mut |item| {
        if cut.get().is_some() {
            held.push(item);
            return;
        }
        batch.push(item);
        if batch.len() == BATCH && open {
            open = emit(std::mem::replace(&mut batch, Vec::with_capacity(BATCH)));
        }
    });
    if !open || (!batch.is_empty() && !emit(batch)) {
        return None;
    }
    if part.end == usize::MAX {
        return Some(End::Last(parsed, errors));
    }
    let at_header = matches!(cut.get(), Some((at, Tok::Action, _)) if at == part.end);
    let faultless = errors.lex.is_empty() && errors.syntax.is_empty() && errors.omitted.count == 0;
    let clean = at_header && faultless && matches!(parsed, Some(Parsed::File));
    Some(if clean { End::Clean(held) } else { End::Unclean })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_start_at_headers_at_least_a_part_apart() {
        let action = "ACTION A\nACTION_1 := 1;\nEND_ACTION\n";
        let src = format!("(* top *)\n{}", action.repeat(PART / 4));
        let starts = part_starts(&src);
        assert!(starts.len() > 3, "{} parts", starts.len());
        assert_eq!(starts[0], 0);
        for pair in starts.windows(2) {
            assert!(pair[1] >= pair[0] + PART, "{pair:?}");
            assert!(src[pair[1]..].starts_with("ACTION A\n"), "{pair:?}");
            assert!(pair[1] < pair[0] + PART + action.len() + 1, "the first header after a part: {pair:?}");
        }
    }

    /// Items and errors of the plain parse and of the parse in parts.
    fn both(src: &str) -> [(Vec<String>, bool, String); 2] {
        let run = |split: bool| {
            let mut items = Vec::new();
            let mut sink = |item| items.push(format!("{item:?}"));
            let (ok, errors) = if split {
                parse_actions_split_giving(src, &mut |item| {
                    sink(item);
                    None
                })
            } else {
                parser::parse_actions(src, &mut sink)
            };
            (items, ok, format!("{errors:?}"))
        };
        [run(false), run(true)]
    }

    #[test]
    fn a_comment_left_open_over_a_part_start_parses_the_same() {
        // The comment runs to the end of the text, so it is kept short: the
        // lexer of an unoptimised build recurses once per character of it.
        let action = "ACTION A\nRecipe.A0 := 1; (* one *)\nEND_ACTION\n";
        let text = action.repeat(3 * PART / action.len());
        let last = *part_starts(&text).last().unwrap();
        let open = "(* never closed\n";
        let src = format!("{}{open}{}", &text[..last], action.replace("*)", "").repeat(3));
        assert_eq!(part_starts(&src).last(), Some(&(last + open.len())), "a part starts after the comment");
        let [plain, split] = both(&src);
        assert!(plain.2.contains("UnclosedComment"), "{}", plain.2);
        assert_eq!(plain, split);
    }

    #[test]
    fn items_given_back_leave_the_parse_the_same() {
        // Clean parts, then one with an error: the items of both threads'
        // parts go back to be freed, and the rest is parsed again after it.
        let action = "ACTION A\nRecipe.A0 := 1; (* one *)\nEND_ACTION\n";
        let mut src = action.repeat(20 * PART / action.len());
        src.push_str("ACTION B\nRecipe.A0 := ;\nEND_ACTION\n");
        src.push_str(&action.repeat(3 * PART / action.len()));
        let [plain, _] = both(&src);
        let mut items = Vec::new();
        let (ok, errors) = parse_actions_split_giving(&src, &mut |item| {
            items.push(format!("{item:?}"));
            Some(item)
        });
        assert!(!plain.2.contains("syntax: []"), "{}", plain.2);
        assert_eq!(plain, (items, ok, format!("{errors:?}")));
    }

    #[test]
    fn a_text_without_headers_is_one_part() {
        assert_eq!(part_starts(&"ACTION_1 := 1;\naction a\n".repeat(PART)), vec![0]);
    }
}
