//! The pool's workers held one to a core (`thread_pinning`). A test binary of its own: the
//! global pool can be built once per process, before anything else uses rayon.

#![cfg(target_os = "linux")]

use ringcontact::thread_pinning::{
    allowed_cores, helper_core_away_from_caller, helper_core_of_caller, pin_pool_workers_to_cores,
    pinning_wanted, Pinning,
};

#[test]
fn each_worker_is_held_to_its_own_core_and_helpers_go_elsewhere() {
    let cores = allowed_cores();
    // A setting that is neither on nor off is refused, and nothing is built.
    let Ok(pinning) = pin_pool_workers_to_cores() else {
        assert!(pinning_wanted().is_err());
        return;
    };
    // Held only when asked (not off), with two cores or more, one worker per core.
    let wanted = pinning_wanted().expect("the setting was read above");
    // (After the call the global pool exists, whoever built it: its size is rayon's default.)
    if cores.len() < 2 || !wanted || rayon::current_num_threads() != cores.len() {
        assert!(matches!(pinning, Pinning::NotPinned(_)), "{pinning:?}");
        assert_eq!(helper_core_away_from_caller(), None);
        assert_eq!(helper_core_of_caller(), None);
        return;
    }
    let workers = rayon::current_num_threads();
    assert_eq!(
        pinning,
        Pinning::Pinned {
            workers,
            cores: cores.clone()
        }
    );
    // Every worker's mask is the one core it was given: worker i on the i-th allowed core.
    let masks = rayon::broadcast(|context| (context.index(), allowed_cores()));
    assert_eq!(masks.len(), cores.len());
    for (i, mask) in masks {
        assert_eq!(mask, vec![cores[i]], "worker {i}");
    }
    // This (test) thread keeps the whole machine; a helper started from it is sent to another
    // core than the one it runs on, and one taking over its core gets that core.
    assert_eq!(allowed_cores(), cores);
    // (Asked twice around the helper's core, so that a move of this thread between the calls,
    // rare but allowed, is not taken for a wrong answer.)
    let settled = (0..100).find_map(|_| {
        let here = helper_core_of_caller().expect("the caller's core");
        let away = helper_core_away_from_caller().expect("a core for the helper");
        (helper_core_of_caller() == Some(here)).then_some((here, away))
    });
    let (here, away) = settled.expect("this thread stays on one core for three calls");
    assert!(cores.contains(&away) && cores.contains(&here));
    assert_ne!(away, here);
    // A second call finds the pool built and says so, changing nothing.
    assert!(matches!(
        pin_pool_workers_to_cores(),
        Ok(Pinning::NotPinned(_))
    ));
}
