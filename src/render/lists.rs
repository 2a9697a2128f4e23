//! Short lists of objects, one per cell of a grid (a tile of pixels), each in the order
//! the objects were added. A cell that would hold more than [`MOST_OBJECTS`] keeps no
//! list: its rays take the usual path (the hierarchy, or every object).

/// The longest list kept. Measured with callgrind at 320x240 on the course scenes
/// spec1, a04, d04, the gallery, the Tachyon twins and the 1,000-object scene of
/// `bench/compare.sh`: 16 gives a04 2-4 % fewer instructions than 8; once the lists ran
/// near to far, 32 gives the 1,000-object scene 1.12x fewer than 16 (64: 1.002x fewer
/// than 32), and the others the same. A tile's hiding planes are the bits of a `u32`, so
/// it is at most 32 (`src/render/tiles.rs`).
pub(crate) const MOST_OBJECTS: usize = 32;

/// The finished lists.
#[derive(Debug, Clone)]
pub(crate) struct Lists {
    /// Cell k's objects are `objects[starts[k]..starts[k + 1]]`, unless `kept[k]` is
    /// false.
    starts: Vec<u32>,
    kept: Vec<bool>,
    objects: Vec<u32>,
}

/// The lists while objects are added: each kept cell's count, and every (cell, object)
/// added to a kept cell, in the order added. One array for all the cells rather than a
/// list each: a list of its own cost each cell an allocation and its release, about
/// half the tiles' build on one ambient plane (callgrind, 640x480).
pub(crate) struct Builder {
    counts: Vec<u32>,
    kept: Vec<bool>,
    added: Vec<(u32, u32)>,
}

impl Builder {
    /// `cells` empty lists; those not `wanted` keep none.
    pub(crate) fn new(cells: usize, wanted: impl Fn(usize) -> bool) -> Builder {
        Builder {
            counts: vec![0; cells],
            kept: (0..cells).map(wanted).collect(),
            added: Vec::new(),
        }
    }

    /// Adds object `index` to `cell`'s list.
    pub(crate) fn add(&mut self, cell: usize, index: usize) {
        if !self.kept[cell] {
            return;
        }
        if self.counts[cell] as usize == MOST_OBJECTS {
            self.kept[cell] = false;
        } else {
            self.counts[cell] += 1;
            self.added.push((cell as u32, index as u32));
        }
    }

    /// Adds object `index` to every cell.
    pub(crate) fn add_everywhere(&mut self, index: usize) {
        (0..self.kept.len()).for_each(|cell| self.add(cell, index));
    }

    /// The lists, packed: each kept cell's objects in the order added.
    pub(crate) fn finish(self) -> Lists {
        let mut starts = Vec::with_capacity(self.counts.len() + 1);
        starts.push(0);
        let mut end = 0;
        for (&count, &kept) in self.counts.iter().zip(&self.kept) {
            end += if kept { count } else { 0 };
            starts.push(end);
        }
        let mut next = starts.clone();
        let mut objects = vec![0; end as usize];
        for (cell, index) in self.added {
            if self.kept[cell as usize] {
                objects[next[cell as usize] as usize] = index;
                next[cell as usize] += 1;
            }
        }
        Lists {
            starts,
            kept: self.kept,
            objects,
        }
    }
}

impl Lists {
    /// The lists of `parts`' cells, the first part's first: the grid of a whole image
    /// from the grids of its bands.
    pub(crate) fn joined(mut parts: Vec<Lists>) -> Lists {
        if parts.len() == 1 {
            return parts.remove(0);
        }
        let mut joined = Lists {
            starts: vec![0],
            kept: Vec::new(),
            objects: Vec::new(),
        };
        for part in parts {
            let offset = joined.objects.len() as u32;
            joined
                .starts
                .extend(part.starts[1..].iter().map(|&s| s + offset));
            joined.kept.extend(part.kept);
            joined.objects.extend(part.objects);
        }
        joined
    }

    /// Cell `cell`'s objects, or `None` when it keeps no list.
    #[inline]
    pub(crate) fn get(&self, cell: usize) -> Option<&[u32]> {
        let range = self.starts[cell] as usize..self.starts[cell + 1] as usize;
        self.kept[cell].then(|| &self.objects[range])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_cell_keeps_its_objects_in_the_order_added_up_to_the_most() {
        // Cell 3 is not wanted; cell 2 is given one object too many.
        let mut lists = Builder::new(4, |cell| cell != 3);
        lists.add(1, 7);
        lists.add(0, 5);
        lists.add(1, 2);
        lists.add(3, 9);
        lists.add_everywhere(4);
        for index in 0..MOST_OBJECTS {
            lists.add(2, 100 + index);
        }
        lists.add(0, 6);
        let lists = lists.finish();
        assert_eq!(lists.get(0), Some(&[5, 4, 6][..]));
        assert_eq!(lists.get(1), Some(&[7, 2, 4][..]));
        assert_eq!(lists.get(2), None);
        assert_eq!(lists.get(3), None);
        // Exactly the most is kept.
        let mut full = Builder::new(1, |_| true);
        (0..MOST_OBJECTS).for_each(|index| full.add(0, index));
        let expected: Vec<u32> = (0..MOST_OBJECTS as u32).collect();
        assert_eq!(full.finish().get(0), Some(&expected[..]));
    }

    #[test]
    fn joined_lists_are_the_parts_cells_in_order() {
        let part = |objects: &[(usize, usize)]| {
            let mut lists = Builder::new(2, |_| true);
            objects
                .iter()
                .for_each(|&(cell, index)| lists.add(cell, index));
            lists.finish()
        };
        let joined = Lists::joined(vec![part(&[(1, 3), (0, 1)]), part(&[(0, 8), (0, 9)])]);
        assert_eq!(joined.get(0), Some(&[1][..]));
        assert_eq!(joined.get(1), Some(&[3][..]));
        assert_eq!(joined.get(2), Some(&[8, 9][..]));
        assert_eq!(joined.get(3), Some(&[][..]));
    }
}
