//! A student's file as pixel blocks, read as a stream: each block is what the program
//! printed for one pixel, in the order printed, with no more than one block held at a
//! time.
//!
//! A block starts (or ends) at a pixel marker: `PIX` or `WRL`, whichever of the two the
//! file prints first. Copies print it at the block's start (the course's own: `PIX`
//! first, `WRL` last) or at its end; the file tells which: if lines that a traced ray
//! prints come before the first marker, the markers close their blocks. What comes
//! before the first block (the model dump) is passed over. A file with no marker at all
//! is one block.

use super::Unreadable;
use super::lex::{Item, Lexer, Said};
use std::io::BufRead;

/// The most items one block may hold: a pixel of a scene of thousands of objects, lights
/// and mirrors prints some tens of thousands. Past it the file is refused, so that memory
/// stays bounded whatever the file holds.
pub const MAX_BLOCK_ITEMS: usize = 400_000;

/// What the program printed for one pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Its place among the file's blocks, from 0.
    pub index: usize,
    /// What it holds, in the order printed.
    pub items: Vec<Item>,
    /// The lines of the file it spans (from 1, inclusive).
    pub lines: (usize, usize),
}

impl Block {
    /// The pixel label (`PIX a b`) and whether it names ROW and COL, if printed.
    pub fn label(&self) -> Option<(i64, i64, bool)> {
        self.items.iter().find_map(|item| match item.said {
            Said::Pix { a, b, row_col } => Some((a, b, row_col)),
            _ => None,
        })
    }

    /// The item of the world point, if printed.
    pub fn world(&self) -> Option<&Item> {
        self.items
            .iter()
            .find(|item| matches!(item.said, Said::World(..)))
    }

    /// Whether it holds anything a traced ray prints.
    pub fn traced(&self) -> bool {
        self.items.iter().any(|item| item.said.traced())
    }
}

/// Which item marks the blocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Marker {
    Pix,
    World,
}

impl Marker {
    fn of(said: &Said) -> Option<Marker> {
        match said {
            Said::Pix { .. } => Some(Marker::Pix),
            Said::World(..) => Some(Marker::World),
            _ => None,
        }
    }
}

/// The blocks of a file, one at a time.
pub struct Blocks<R> {
    lexer: Lexer<R>,
    /// The marker and whether it closes its block; `None` before the first marker.
    marker: Option<(Marker, bool)>,
    /// The block being gathered.
    current: Vec<Item>,
    /// The line the current block starts on.
    start: usize,
    /// Blocks handed out so far.
    count: usize,
    finished: bool,
}

impl<R: BufRead> Blocks<R> {
    /// The blocks of `input`.
    pub fn new(input: R) -> Blocks<R> {
        Blocks {
            lexer: Lexer::new(input),
            marker: None,
            current: Vec::new(),
            start: 1,
            count: 0,
            finished: false,
        }
    }

    /// The lines read so far.
    pub fn lines(&self) -> usize {
        self.lexer.lines()
    }

    /// The next block, or `None` at the end of the file.
    pub fn next_block(&mut self) -> Result<Option<Block>, Unreadable> {
        if self.finished {
            return Ok(None);
        }
        loop {
            let item = self
                .lexer
                .next_item()
                .map_err(|error| Unreadable(format!("it cannot be read: {error}")))?;
            let Some(item) = item else {
                self.finished = true;
                // The last block; or, in a file without markers, the only one.
                let items = std::mem::take(&mut self.current);
                let end = self.lexer.lines();
                // A block opened by a marker is one whatever it holds; lines after the
                // last closing marker, or in a file without markers, only if a ray's.
                let opened = matches!(self.marker, Some((_, false)));
                if items.is_empty() || !(opened || items.iter().any(|i| i.said.traced())) {
                    return Ok(None);
                }
                return Ok(Some(self.block(items, end)));
            };
            let marker = Marker::of(&item.said);
            match (self.marker, marker) {
                (None, Some(kind)) => {
                    // The first marker: it closes blocks if a ray's lines came before it.
                    let closes = self.current.iter().any(|i| i.said.traced());
                    self.marker = Some((kind, closes));
                    if closes {
                        return Ok(Some(self.closed_by(item)));
                    }
                    // What came before was a model dump.
                    self.current.clear();
                    self.start = item.line;
                    self.current.push(item);
                }
                (Some((kind, false)), Some(found)) if kind == found => {
                    let line = item.line;
                    let items = std::mem::replace(&mut self.current, vec![item]);
                    let block = self.block(items, line - 1);
                    self.start = line;
                    return Ok(Some(block));
                }
                (Some((kind, true)), Some(found)) if kind == found => {
                    return Ok(Some(self.closed_by(item)));
                }
                _ => {
                    if self.current.len() >= MAX_BLOCK_ITEMS {
                        return Err(Unreadable(format!(
                            "its lines from line {} on hold over {MAX_BLOCK_ITEMS} traced \
                             values with no pixel marker (PIX or WRL) between them: no pixel \
                             of a course scene prints that many",
                            self.start
                        )));
                    }
                    self.current.push(item);
                }
            }
        }
    }

    /// The block gathered so far, closed by the marker `item`.
    fn closed_by(&mut self, item: Item) -> Block {
        let line = item.line;
        let mut items = std::mem::take(&mut self.current);
        items.push(item);
        let block = self.block(items, line);
        self.start = line + 1;
        block
    }

    fn block(&mut self, items: Vec<Item>, end: usize) -> Block {
        let index = self.count;
        self.count += 1;
        Block {
            index,
            items,
            lines: (self.start, end.max(self.start)),
        }
    }
}

/// Every block of a small text (for tests).
#[cfg(test)]
pub(crate) fn blocks(text: &str) -> Vec<Block> {
    let mut blocks = Blocks::new(text.as_bytes());
    let mut out = Vec::new();
    while let Some(block) = blocks.next_block().unwrap() {
        out.push(block);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_block_runs_from_one_pix_to_the_next_and_the_dump_is_passed_over() {
        let text = "Dumping\nEmissivity 1 2 3\nPIX 0 0 -\nFND 1: 2.0 -\nWRL (1.0, 2.0)\n\
                    PIX 1 0 -\nFND 1: -1 -\nWRL (3.0, 2.0)\nNow deleting scene\n";
        let blocks = blocks(text);
        assert_eq!(blocks.len(), 2);
        assert_eq!(blocks[0].lines, (3, 5));
        assert_eq!(blocks[1].lines, (6, 9));
        assert_eq!(blocks[1].label(), Some((1, 0, false)));
        assert!(blocks[1].world().is_some_and(|w| w.line == 8));
    }

    #[test]
    fn markers_that_close_their_blocks() {
        // WRL printed after the pixel's lines, and no PIX.
        let text = "FND 1: 2.0 -\nWRL (1.0, 2.0)\nFND 1: 3.0 -\nWRL (3.0, 2.0)\n";
        let blocks = blocks(text);
        assert_eq!(blocks.len(), 2);
        assert_eq!(blocks[1].lines, (3, 4));
        assert!(blocks.iter().all(Block::traced));
    }

    #[test]
    fn no_marker_is_one_block() {
        let blocks = blocks("x\nFND 1: 2.0 -\nHIT 1: 2.0 (1, 2, 3)\n");
        assert_eq!(blocks.len(), 1);
        assert_eq!(blocks[0].items.len(), 2);
        assert!(
            super::Blocks::new(&b"\n\n\n"[..])
                .next_block()
                .unwrap()
                .is_none()
        );
    }
}
