//! A work budget for the exact stages of many verdicts: a search over candidate curves (the
//! repair's handle lengths, say) runs under [`with_exact_budget`], and each verdict whose
//! floating-point filter cannot decide spends the predicted cost of its exact stage
//! (`exact::signs::exact_cost`, the model of [`crate::exact::signs::EXACT_BUDGET`]). Once the
//! budget is spent, a verdict that would need exact arithmetic is refused with
//! [`crate::Error::NoConvergence`] instead of being computed: never guessed, and a search
//! takes a refused candidate as not proven. The filter's own verdicts cost nothing and are
//! never refused.
//!
//! Why: one exact stage on a cubic whose coordinates span 600 orders of magnitude takes
//! about 10 ms (21,000-bit coefficients), within the single verdict's budget; a search that
//! tries 1,500 such candidates took 20 s. On a font's or a drawing's coordinates an exact
//! stage costs a hundred times less and a search never comes near the budget.
//!
//! The budget is per thread, like [`crate::deadline`]; verdicts without one are never
//! refused. Nested budgets spend from both: the inner one starts with what is left of the
//! outer one, at most.

use std::cell::Cell;

thread_local! {
    static LEFT: Cell<Option<f64>> = const { Cell::new(None) };
    static REFUSED: Cell<bool> = const { Cell::new(false) };
}

/// The exact work one search may spend, in the cost model's units: half of what one verdict
/// may cost at most. The repair's search of one cubic (at most 2,900 candidates) may give
/// every candidate an exact stage while the coordinates span up to 30 orders of magnitude;
/// at 600 orders, about 60 of them (under a second here).
pub const SEARCH_EXACT_BUDGET: f64 = crate::exact::signs::EXACT_BUDGET / 2.0;

/// Runs `f` with the exact stages of its verdicts limited to `units` in all (see the module
/// docs). Returns `f`'s value and whether some verdict was refused for want of budget.
pub fn with_exact_budget<T>(units: f64, f: impl FnOnce() -> T) -> (T, bool) {
    let outer = LEFT.with(|l| l.get());
    let outer_refused = REFUSED.with(|r| r.replace(false));
    let start = outer.map_or(units, |o| o.min(units));
    LEFT.with(|l| l.set(Some(start)));
    struct Restore(Option<f64>, f64, bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            let spent = self.1 - LEFT.with(|l| l.get()).unwrap_or(self.1);
            LEFT.with(|l| l.set(self.0.map(|o| o - spent)));
            let inner = REFUSED.with(|r| r.get());
            REFUSED.with(|r| r.set(self.2 || inner));
        }
    }
    let restore = Restore(outer, start, outer_refused);
    let value = f();
    let refused = REFUSED.with(|r| r.get());
    drop(restore);
    (value, refused)
}

/// Whether an exact stage of predicted `cost` may run; spends it when it may. Without a
/// budget on this thread it always may.
pub(super) fn spend(cost: f64) -> bool {
    LEFT.with(|l| match l.get() {
        None => true,
        Some(left) if cost <= left => {
            l.set(Some(left - cost));
            true
        }
        Some(_) => {
            REFUSED.with(|r| r.set(true));
            false
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_budget_is_spent_refused_and_restored() {
        assert!(spend(1e30), "no budget: always");
        let ((), refused) = with_exact_budget(10.0, || {
            assert!(spend(6.0));
            assert!(!spend(6.0), "4 left");
            assert!(spend(4.0));
        });
        assert!(refused);
        let ((), refused) = with_exact_budget(10.0, || {
            let ((), inner) = with_exact_budget(100.0, || assert!(spend(7.0)));
            assert!(!inner);
            assert!(!spend(4.0), "the inner one spent 7 of the outer 10");
        });
        assert!(refused, "the outer one saw the refusal");
        assert!(spend(1e30), "restored: no budget");
    }

    /// The claims of [`SEARCH_EXACT_BUDGET`]'s docs, in the cost model.
    #[test]
    fn a_search_affords_every_candidate_up_to_30_orders_of_magnitude() {
        use kurbo::Point;
        let cost = |small: f64, big: f64| {
            let pts = [
                Point::new(0.0, small),
                Point::new(big, 0.3),
                Point::new(2.0 * big, big),
                Point::new(3.0 * big, 0.0),
            ];
            let inp = super::super::certified::Input::new(&pts, None).unwrap();
            super::super::certified::predicted_cost(&inp, super::super::exact_test_degree(3, false))
        };
        assert!(2900.0 * cost(1e-15, 1e15) <= SEARCH_EXACT_BUDGET);
        let wide = SEARCH_EXACT_BUDGET / cost(1e-300, 1e300);
        assert!((40.0..100.0).contains(&wide), "{wide}");
    }
}
