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

/// The lists while objects are added.
pub(crate) struct Builder {
    lists: Vec<Vec<u32>>,
    kept: Vec<bool>,
}

impl Builder {
    /// `cells` empty lists; those not `wanted` keep none.
    pub(crate) fn new(cells: usize, wanted: impl Fn(usize) -> bool) -> Builder {
        Builder {
            lists: vec![Vec::new(); cells],
            kept: (0..cells).map(wanted).collect(),
        }
    }

    /// Adds object `index` to `cell`'s list.
    pub(crate) fn add(&mut self, cell: usize, index: usize) {
        if !self.kept[cell] {
            return;
        }
        if self.lists[cell].len() == MOST_OBJECTS {
            self.kept[cell] = false;
            self.lists[cell] = Vec::new();
        } else {
            self.lists[cell].push(index as u32);
        }
    }

    /// Adds object `index` to every cell.
    pub(crate) fn add_everywhere(&mut self, index: usize) {
        (0..self.kept.len()).for_each(|cell| self.add(cell, index));
    }

    /// The lists, packed.
    pub(crate) fn finish(self) -> Lists {
        let mut starts = Vec::with_capacity(self.lists.len() + 1);
        let mut objects = Vec::new();
        starts.push(0);
        for list in &self.lists {
            objects.extend_from_slice(list);
            starts.push(objects.len() as u32);
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
