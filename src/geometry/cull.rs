//! Back-face culling, decided on the **snapped** screen positions, so that facing and coverage
//! can never disagree: a triangle whose float area is a hair positive but whose snapped area is
//! negative is culled, and one that collapses to zero area when snapped is counted as
//! degenerate and never divides by its area.

pub use crate::kernel::records::{facing, signed_area2, Facing};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::records::ScreenVertex;

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
