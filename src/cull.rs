//! Back-face culling, decided on the **snapped** screen positions, so that facing and coverage
//! can never disagree: a triangle whose float area is a hair positive but whose snapped area is
//! negative is culled, and one that collapses to zero area when snapped is counted as
//! degenerate and never divides by its area.

use crate::project::ScreenVertex;

/// What culling decided for a snapped triangle.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Counter-clockwise as the viewer sees it: drawn.
    Front,
    /// Clockwise as the viewer sees it: culled.
    Back,
    /// Zero snapped area: skipped.
    Degenerate,
}

/// Twice the signed area of a snapped triangle in subpixels², positive for front faces
/// (counter-clockwise as the viewer sees them, which is clockwise in y-down screen space).
#[must_use]
pub fn signed_area2(a: &ScreenVertex, b: &ScreenVertex, c: &ScreenVertex) -> i64 {
    // Coordinates within ±COORD_LIMIT (2¹⁴ − 1): differences ≤ 32 766 and 2·32 766² < 2³¹,
    // so 32-bit arithmetic is exact (two single-instruction multiplies on a Cortex-M0).
    let (x0, y0) = (a.x as i32, a.y as i32);
    let area = (c.x as i32 - x0) * (b.y as i32 - y0) - (b.x as i32 - x0) * (c.y as i32 - y0);
    area as i64
}

/// Classifies a snapped triangle.
#[must_use]
pub fn facing(a: &ScreenVertex, b: &ScreenVertex, c: &ScreenVertex) -> Facing {
    match signed_area2(a, b, c) {
        0 => Facing::Degenerate,
        x if x > 0 => Facing::Front,
        _ => Facing::Back,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facing_sign() {
        let v = |x: i16, y: i16| ScreenVertex {
            x,
            y,
            ..Default::default()
        };
        // Counter-clockwise with y up = clockwise on a y-down screen: front.
        assert!(signed_area2(&v(0, 0), &v(16, 0), &v(0, -16)) > 0);
        assert!(signed_area2(&v(0, 0), &v(0, -16), &v(16, 0)) < 0);
        assert_eq!(signed_area2(&v(0, 0), &v(16, 16), &v(32, 32)), 0);
        assert_eq!(facing(&v(0, 0), &v(16, 0), &v(0, -16)), Facing::Front);
        assert_eq!(facing(&v(0, 0), &v(0, -16), &v(16, 0)), Facing::Back);
        assert_eq!(facing(&v(5, 5), &v(5, 5), &v(9, 1)), Facing::Degenerate);
    }
}
