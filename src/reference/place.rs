//! Where a bounce's sender lies for the camera: the report's split of the truth's bounce into
//! what the screen can send and what it cannot (`image.rs` places each sender, `scene.rs` sums
//! the bounce by place), and, for what it cannot, whether a second depth layer would hold it.

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

/// Where a sender lies ([`SenderPlace`]), and whether the first two surfaces on its pixel's eye
/// ray hold it: the one the depth buffer shows (for a sender facing away, a sheet seen from its
/// other side) or the one right behind it (a fin's far face, a sphere's back), which a second
/// depth layer would add. The senders of the seen place are in the first; those off the screen
/// in none.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placement {
    pub place: SenderPlace,
    pub in_two_layers: bool,
}

impl Placement {
    /// The bounce's sums a pixel keeps: each place for its senders in the first two layers, then
    /// each place for the others.
    pub const COUNT: usize = 2 * SenderPlace::ALL.len();

    pub fn seen() -> Self {
        Self { place: SenderPlace::Seen, in_two_layers: true }
    }

    /// Its sum's index: `place` within the first two layers, `4 + place` beyond them.
    pub fn index(self) -> usize {
        self.place as usize + if self.in_two_layers { 0 } else { SenderPlace::ALL.len() }
    }
}

/// A pixel's sums by [`Placement::index`].
pub type Places = [f32; Placement::COUNT];
