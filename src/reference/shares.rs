//! The truth's bounce, and the sky its occluders block, shared out by where the senders and the
//! occluders lie for the camera ([`Placement`]): what the screen can reach and what it cannot.

use super::image::Reference;
use super::place::{Placement, Places, SenderPlace};

impl Reference {
    /// The shares of the truth's bounce (its luminance over the measured pixels) by where its
    /// senders lie ([`SenderPlace::ALL`]); `None` where there is no bounce.
    pub fn bounce_shares(&self) -> Option<[f64; 4]> {
        placed_shares(&self.bounce_by_place, &self.valid).map(by_place)
    }

    /// The shares of the sky the truth's occluders block (the sky's luminance each ray that hits
    /// something would have brought) by where the occluders lie ([`SenderPlace::ALL`]): what a
    /// depth buffer holds to block, and what it does not; `None` where nothing is blocked.
    pub fn blocked_shares(&self) -> Option<[f64; 4]> {
        placed_shares(&self.blocked_by_place, &self.valid).map(by_place)
    }

    /// The shares of the truth's bounce from senders of each place ([`SenderPlace::ALL`]) that
    /// the first two surfaces on their eye ray hold ([`Placement`]): of the hidden and the
    /// facing away, what a second depth layer could reach.
    pub fn two_layer_shares(&self) -> Option<[f64; 4]> {
        placed_shares(&self.bounce_by_place, &self.valid).map(|s| std::array::from_fn(|k| s[k]))
    }

    /// The mean luminance of the truth's bounce from senders the camera sees, over `pixels`.
    pub fn seen_bounce(&self, pixels: &[usize]) -> f64 {
        let seen = Placement::seen().index();
        pixels.iter().map(|&i| self.bounce_by_place[i][seen] as f64).sum::<f64>() / pixels.len().max(1) as f64
    }
}

/// The shares of the sums `of` over the `valid` pixels by [`Placement::index`].
fn placed_shares(of: &[Places], valid: &[bool]) -> Option<[f64; Placement::COUNT]> {
    let mut sums = [0.0f64; Placement::COUNT];
    for (by_place, _) in of.iter().zip(valid).filter(|(_, v)| **v) {
        for (sum, b) in sums.iter_mut().zip(by_place) {
            *sum += *b as f64;
        }
    }
    let total: f64 = sums.iter().sum();
    (total > 0.0).then(|| sums.map(|s| s / total))
}

/// Shares by place, within two layers or not.
fn by_place(s: [f64; Placement::COUNT]) -> [f64; 4] {
    std::array::from_fn(|k| s[k] + s[k + SenderPlace::ALL.len()])
}
