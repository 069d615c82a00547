//! Where a bounce's sender lies for the camera: the report's split of the truth's bounce into
//! what the screen can send and what it cannot (`image.rs` places each sender, `scene.rs` sums
//! the bounce by place).

/// Where a bounce's sender lies for the camera: what the screen can and cannot send from (the
/// report splits the truth's bounce by it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SenderPlace {
    /// The depth buffer holds it (at its pixel, within a tolerance), its lit side towards the eye.
    Seen,
    /// On screen, facing the eye, but not where the depth buffer is: behind a nearer surface.
    Hidden,
    /// Outside the view (beside the frustum, or behind the eye).
    OffScreen,
    /// On screen, but the side that lights the receiver faces away from the eye (an underside, a
    /// back face).
    FacingAway,
}

impl SenderPlace {
    pub const ALL: [SenderPlace; 4] =
        [SenderPlace::Seen, SenderPlace::Hidden, SenderPlace::OffScreen, SenderPlace::FacingAway];

    pub fn name(self) -> &'static str {
        match self {
            SenderPlace::Seen => "seen",
            SenderPlace::Hidden => "hidden",
            SenderPlace::OffScreen => "off screen",
            SenderPlace::FacingAway => "facing away",
        }
    }
}
