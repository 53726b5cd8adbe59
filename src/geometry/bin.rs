//! Binning: the triangles stored by the geometry stage, sorted by their first covered row
//! with one counting pass (a bucket sort over the rows), so that the strip pass takes each
//! row's new triangles in order without a list link per triangle.

use crate::kernel::records::TriRecord;
use crate::num::scalar::Scalar;
use crate::scene::color::TargetColor;

use crate::geometry::stores::Stores;
use crate::kernel::records::bucket_row;

impl<
        S: Scalar,
        C: TargetColor,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
    > Stores<S, C, H, VERTS, TRIS, XV, XA>
{
    /// The bucket of a stored triangle (see [`bucket_row`]).
    pub(crate) fn first_row(&self, t: &TriRecord) -> usize {
        // Element by element: on a Cortex-M0 `array::map` stays a call (`try_from_fn`).
        let [i, j, k] = t.indices();
        let (a, b, c) = (self.verts[i].y, self.verts[j].y, self.verts[k].y);
        let (a, b, c) = (a as i32, b as i32, c as i32);
        bucket_row(a.min(b).min(c))
    }

    /// Sorts the triangles by first row in place (an American-flag bucket sort: every record
    /// moves at most once), turning `heads` from counts into bucket starts. No list links are
    /// stored, which saves 2 bytes per triangle.
    pub(crate) fn sort_buckets(&mut self) {
        let vh = self.vh;
        let mut acc = 0u16;
        for r in 0..vh {
            let n = self.heads[r];
            self.heads[r] = acc;
            self.starts[r] = acc as i16;
            acc += n;
        }
        let len = self.tris.len();
        for b in 0..vh {
            let end = if b + 1 < vh {
                self.heads[b + 1] as usize
            } else {
                len
            };
            // The record at bucket b's cursor goes to its own bucket's cursor, and the record
            // it displaces is placed next, until one belongs to bucket b (as swapping the two
            // records each time would place them, with one read and one write a step).
            let mut i = self.starts[b] as usize;
            while i < end {
                let Some(&first) = self.tris.get(i) else {
                    break;
                };
                let mut t = first;
                let mut tb = self.first_row(&t);
                while tb != b {
                    // tb > b: every earlier bucket is complete.
                    let Some(j) = self.starts.get_mut(tb) else {
                        break;
                    };
                    let Some(slot) = self.tris.get_mut(*j as usize) else {
                        break;
                    };
                    *j += 1;
                    core::mem::swap(&mut t, slot);
                    tb = self.first_row(&t);
                }
                if let Some(slot) = self.tris.get_mut(i) {
                    *slot = t;
                }
                i += 1;
            }
            self.starts[b] = i as i16;
        }
    }
}
