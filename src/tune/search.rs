//! Tune's search over the measured settings: the Pareto front of time against error, the pick
//! for a budget and a target, and the focus whose neighbours are measured next.

use super::space::Candidate;

/// Errors within this share of each other count as equal when picking: the cheaper is taken. The
/// truth's noise and the views' spread make smaller differences meaningless, and on cornell the
/// last 1% of error within a budget costs up to half the frame again.
pub const EQUAL_ERROR: f64 = 0.01;
/// One measured setting: its time (on the report's view) and its errors, averaged over the views.
#[derive(Clone, Debug)]
pub struct Point {
    /// The search's setting (`None` for Off and for the `also` presets).
    pub candidate: Option<Candidate>,
    /// The setting's knobs (`None` for Off), and the preset's name for an `also` preset.
    pub knobs: Option<crate::knobs::Knobs>,
    pub name: Option<String>,
    pub ms: f64,
    /// Frames timed for `ms`.
    pub frames_timed: usize,
    pub hdr_rmse: f64,
    pub do_rmse: Option<f64>,
    pub flip: f64,
    /// HDR RMSE of each view.
    pub hdr_per_view: Vec<f64>,
    /// On the Pareto front of time against HDR error.
    pub front: bool,
}

/// Why the pick is what it is, when it is not plainly "the most accurate within the budget".
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// The most accurate setting within the budget.
    Best,
    /// The cheapest that reaches the target error.
    Target,
    /// No setting measured reaches the target within the budget: the most accurate is picked.
    TargetMissed,
    /// Even the most accurate setting measured fits: the budget does not bind.
    NotBinding,
    /// No setting measured fits the budget; nothing is picked.
    BelowCheapest,
}

/// Marks the points no other point beats on both time and HDR error.
pub(super) fn mark_front(points: &mut [Point]) {
    let all: Vec<(f64, f64)> = points.iter().map(|p| (p.ms, p.hdr_rmse)).collect();
    for (i, p) in points.iter_mut().enumerate() {
        let (ms, e) = all[i];
        p.front = !all.iter().enumerate().any(|(j, &(m2, e2))| j != i && m2 <= ms && e2 <= e && (m2 < ms || e2 < e));
    }
}

/// The pick among `points` for a budget and a target, and why.
pub(super) fn choose(points: &[Point], budget: Option<f64>, target: Option<f64>) -> (Option<usize>, Verdict) {
    let within: Vec<usize> = (0..points.len()).filter(|&i| budget.is_none_or(|b| points[i].ms <= b)).collect();
    let most_accurate = within.iter().copied().min_by(|&a, &b| points[a].hdr_rmse.total_cmp(&points[b].hdr_rmse));
    let Some(most_accurate) = most_accurate else {
        return (None, Verdict::BelowCheapest);
    };
    // The cheapest of those as accurate as the most accurate, within [`EQUAL_ERROR`].
    let as_good = points[most_accurate].hdr_rmse * (1.0 + EQUAL_ERROR);
    let best = within
        .iter()
        .copied()
        .filter(|&i| points[i].hdr_rmse <= as_good)
        .min_by(|&a, &b| points[a].ms.total_cmp(&points[b].ms))
        .unwrap_or(most_accurate);
    if let Some(e) = target {
        let reaching = within.iter().copied().filter(|&i| points[i].hdr_rmse <= e);
        return match reaching.min_by(|&a, &b| points[a].ms.total_cmp(&points[b].ms)) {
            Some(i) => (Some(i), Verdict::Target),
            None => (Some(best), Verdict::TargetMissed),
        };
    }
    let overall = (0..points.len()).min_by(|&a, &b| points[a].hdr_rmse.total_cmp(&points[b].hdr_rmse));
    if overall == Some(most_accurate) && points.iter().all(|p| budget.is_none_or(|b| p.ms <= b)) {
        (Some(best), Verdict::NotBinding)
    } else {
        (Some(best), Verdict::Best)
    }
}

/// Where a setting of the focus stands, and so which of its neighbours are worth measuring.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Role {
    /// The pick: every neighbour.
    Pick,
    /// The front's setting just dearer than the pick (often over the budget): the neighbours
    /// that cost no more, which may fit the budget and keep its accuracy.
    Dearer,
    /// The front's setting just cheaper: the neighbours that cost no less.
    Cheaper,
}

impl Role {
    pub(super) fn neighbours(self, c: &Candidate) -> Vec<Candidate> {
        let keep = |n: &Candidate| match self {
            Role::Pick => true,
            Role::Dearer => c.dearer(n) != Some(true),
            Role::Cheaper => c.dearer(n) != Some(false),
        };
        c.neighbours().into_iter().filter(keep).collect()
    }
}

/// The settings to expand next, in the order to try them: the pick and the front's settings
/// either side of it in time; on odd `turn`s the dearer first, so a start just over the budget
/// (the defaults, often) is walked down while the pick climbs.
pub(super) fn focus(points: &[Point], budget: Option<f64>, target: Option<f64>, turn: usize) -> Vec<(usize, Role)> {
    let mut front: Vec<usize> = (0..points.len()).filter(|&i| points[i].front).collect();
    front.sort_by(|&a, &b| points[a].ms.total_cmp(&points[b].ms));
    let (pick, _) = choose(points, budget, target);
    // Below the cheapest: the cheapest setting is where cheaper ones are found.
    let pick = pick.unwrap_or_else(|| front[0]);
    let at = front.iter().position(|&i| i == pick);
    let dearer = at.and_then(|k| front.get(k + 1)).map(|&i| (i, Role::Dearer));
    let cheaper = at.and_then(|k| k.checked_sub(1)).map(|k| (front[k], Role::Cheaper));
    let mut out = Vec::new();
    if turn % 2 == 1 {
        out.extend(dearer);
        out.push((pick, Role::Pick));
    } else {
        out.push((pick, Role::Pick));
        out.extend(dearer);
    }
    out.extend(cheaper);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(ms: f64, hdr_rmse: f64) -> Point {
        Point {
            candidate: None,
            knobs: None,
            name: None,
            ms,
            frames_timed: 1,
            hdr_rmse,
            do_rmse: None,
            flip: 0.0,
            hdr_per_view: vec![hdr_rmse],
            front: false,
        }
    }

    #[test]
    fn the_pick_is_the_most_accurate_within_the_budget_or_the_cheapest_reaching_the_target() {
        let mut points = vec![point(5.0, 0.09), point(10.0, 0.05), point(12.0, 0.06), point(20.0, 0.03)];
        mark_front(&mut points);
        assert_eq!(points.iter().map(|p| p.front).collect::<Vec<_>>(), [true, true, false, true]);
        // Within 1% of the most accurate is as good: the cheaper of the two is taken.
        let mut close = points.clone();
        close.push(point(14.0, 0.0499));
        assert_eq!(choose(&close, Some(15.0), None), (Some(1), Verdict::Best));
        close.push(point(14.5, 0.0480));
        assert_eq!(choose(&close, Some(15.0), None), (Some(5), Verdict::Best));
        assert_eq!(choose(&points, Some(15.0), None), (Some(1), Verdict::Best));
        assert_eq!(choose(&points, Some(4.0), None), (None, Verdict::BelowCheapest));
        assert_eq!(choose(&points, Some(25.0), None), (Some(3), Verdict::NotBinding));
        assert_eq!(choose(&points, None, Some(0.06)), (Some(1), Verdict::Target));
        assert_eq!(choose(&points, Some(15.0), Some(0.04)), (Some(1), Verdict::TargetMissed));
        // The focus: the pick and the front's settings either side of it in time.
        let (p, d, c) = (Role::Pick, Role::Dearer, Role::Cheaper);
        assert_eq!(focus(&points, Some(15.0), None, 0), [(1, p), (3, d), (0, c)]);
        assert_eq!(focus(&points, Some(15.0), None, 1), [(3, d), (1, p), (0, c)]);
        assert_eq!(focus(&points, Some(4.0), None, 0), [(0, p), (1, d)]);
    }
}
