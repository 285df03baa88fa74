//! One rayon worker per core, each held to its own core.
//!
//! A solve hands work from one core to the other many times (`rayon::join`: the first half runs
//! here, the second is taken by the other worker). When that worker is asleep, the kernel wakes
//! it, and Linux's scheduler may place the woken thread on the waker's core, which is busy,
//! instead of the idle one: the second half then starts only when the first has ended, and the
//! two cores' work runs on one. Measured on the 2-core virtual machine this project is developed
//! on (kernel 6.18; a scratch program that keeps the calling thread busy for a while, then joins
//! two halves of 0.2 or 2 ms and records when each starts, 60 joins): once the other core had
//! been idle for 5 ms, the second half started after a median of 1.2-2.0 ms, that is mostly only
//! once the first had ended, and after 20 ms idle after 2.0 ms (90th percentile 2.04 ms), against
//! medians of 35-36 µs (90th percentiles 45-51 µs) with each worker held to its own core. A
//! worker held to one core can only be woken there: the kernel then sends the idle core an
//! interrupt rather than queueing the worker behind a busy thread. New threads fare the same:
//! after two of five idle times, at least a tenth of the threads started beside a busy one ran
//! only once its 3 ms of work had ended (90th percentiles of 1.4 and 2.6 ms).
//!
//! [`pin_pool_workers_to_cores`] builds rayon's global pool that way. The program's other
//! threads (its main thread, child processes such as gmsh) keep the whole machine. Set
//! [`PIN_VARIABLE`] to `0` to leave the pool to the scheduler (for example when another program
//! shares the machine's cores).

use std::sync::OnceLock;

/// Environment variable that turns the pinning off (`0`) or on (`1`, the default); see
/// [`pinning_wanted`] for the values it takes.
pub const PIN_VARIABLE: &str = "RINGCONTACT_PIN_THREADS";

/// The setting a value of [`PIN_VARIABLE`] names: `0`, `off`, `false` or `no` turn the pinning
/// off, `1`, `on`, `true` or `yes` on (any case, blanks around ignored); `None` for anything
/// else.
pub fn parse_pin_setting(value: &str) -> Option<bool> {
    match value.trim().to_ascii_lowercase().as_str() {
        "0" | "off" | "false" | "no" => Some(false),
        "1" | "on" | "true" | "yes" => Some(true),
        _ => None,
    }
}

/// Whether the environment asks for the pool's workers to be held to cores: yes when
/// [`PIN_VARIABLE`] is unset or empty, else its [`parse_pin_setting`]; an error naming the
/// variable, its value and the values it takes when it is none of them (a typo such as `of`
/// must not silently leave the default on).
pub fn pinning_wanted() -> Result<bool, String> {
    let Some(raw) = std::env::var_os(PIN_VARIABLE) else {
        return Ok(true);
    };
    let value = raw.to_string_lossy();
    if value.trim().is_empty() {
        return Ok(true);
    }
    parse_pin_setting(&value).ok_or_else(|| {
        format!(
            "{PIN_VARIABLE}={value:?} is not a setting: use 0 or off (leave the solver's workers \
             to the scheduler) or 1 or on (each worker held to its own core, the default)"
        )
    })
}

/// The allowed cores, set when the pool's workers were pinned: helper threads are then held
/// away from the core of the thread that starts them ([`helper_core_away_from_caller`]).
static PINNED_CORES: OnceLock<Vec<usize>> = OnceLock::new();

/// What [`pin_pool_workers_to_cores`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Pinning {
    /// The global pool was built with worker `i` held to `cores[i]`.
    Pinned { workers: usize, cores: Vec<usize> },
    /// Not pinned, and why.
    NotPinned(String),
}

/// The cores this process may run on (its affinity mask), ascending; empty when unknown.
pub fn allowed_cores() -> Vec<usize> {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: `sched_getaffinity(0, ...)` fills a zeroed `cpu_set_t` of the size given with
        // the calling thread's mask; `CPU_ISSET` reads that set within its size.
        unsafe {
            let mut set: libc::cpu_set_t = std::mem::zeroed();
            if libc::sched_getaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &mut set) != 0 {
                return Vec::new();
            }
            (0..libc::CPU_SETSIZE as usize)
                .filter(|&cpu| libc::CPU_ISSET(cpu, &set))
                .collect()
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        Vec::new()
    }
}

/// Hold the calling thread to `core`; whether the kernel accepted it.
fn hold_current_thread_to(core: usize) -> bool {
    #[cfg(target_os = "linux")]
    {
        if core >= libc::CPU_SETSIZE as usize {
            return false;
        }
        // SAFETY: a zeroed `cpu_set_t` with one bit set below `CPU_SETSIZE`, passed with its own
        // size; `sched_setaffinity(0, ...)` changes only the calling thread.
        unsafe {
            let mut set: libc::cpu_set_t = std::mem::zeroed();
            libc::CPU_SET(core, &mut set);
            libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &set) == 0
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = core;
        false
    }
}

/// Build rayon's global pool with worker `i` held to the `i`-th allowed core, unless
/// [`pinning_wanted`] says no, fewer than two cores are allowed, or the pool already exists; an
/// error (nothing built) when [`PIN_VARIABLE`] holds no setting ([`pinning_wanted`]'s). A pool
/// of another size than the allowed cores (`RAYON_NUM_THREADS`, or a CPU quota that rayon's
/// count honours) is built but left to the scheduler: held workers could not move off cores that
/// other processes of the same kind would hold as well. Call once, at the start of `main`,
/// before anything uses rayon.
pub fn pin_pool_workers_to_cores() -> Result<Pinning, String> {
    if !pinning_wanted()? {
        return Ok(Pinning::NotPinned(format!("{PIN_VARIABLE} is off")));
    }
    Ok(pin_to_allowed_cores())
}

/// [`pin_pool_workers_to_cores`] once the setting asked for it.
fn pin_to_allowed_cores() -> Pinning {
    let cores = allowed_cores();
    if cores.len() < 2 {
        return Pinning::NotPinned(format!("{} allowed core(s)", cores.len()));
    }
    let for_workers = cores.clone();
    let built = rayon::ThreadPoolBuilder::new()
        .start_handler(move |i| {
            // The handler runs on the new worker, so the count is its pool's. A refusal (a core
            // taken away meanwhile) leaves the worker to the scheduler.
            if rayon::current_num_threads() == for_workers.len() {
                hold_current_thread_to(for_workers[i]);
            }
        })
        .build_global();
    if let Err(e) = built {
        return Pinning::NotPinned(format!("rayon's global pool: {e}"));
    }
    let workers = rayon::current_num_threads();
    if workers != cores.len() {
        return Pinning::NotPinned(format!(
            "a pool of {workers} workers for {} allowed cores",
            cores.len()
        ));
    }
    let _ = PINNED_CORES.set(cores.clone());
    Pinning::Pinned { workers, cores }
}

/// For a helper thread about to be started beside the calling thread (the mesh read's scans
/// and hash, beside the parse): a core other than the caller's current one, when the pool was
/// pinned ([`pin_pool_workers_to_cores`]); `None` otherwise. The helper passes it to
/// [`hold_helper_to`] first thing: a new thread may otherwise be queued behind its busy starter
/// while the other core idles (the same scheduling as the pool's, see the module).
pub fn helper_core_away_from_caller() -> Option<usize> {
    let cores = PINNED_CORES.get()?;
    let current = current_core();
    cores.iter().copied().find(|&c| Some(c) != current)
}

/// For a helper thread that takes over the caller's core (the caller is about to end, as the
/// read's scan thread does once it has started the hash): that core, when the pool was pinned
/// and it is one of the allowed cores; `None` otherwise.
pub fn helper_core_of_caller() -> Option<usize> {
    let cores = PINNED_CORES.get()?;
    current_core().filter(|c| cores.contains(c))
}

/// The core the calling thread runs on now.
fn current_core() -> Option<usize> {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: reads the calling thread's CPU number (-1 on failure).
        let core = unsafe { libc::sched_getcpu() };
        usize::try_from(core).ok()
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}

/// Hold the calling (helper) thread to `core` when there is one (see
/// [`helper_core_away_from_caller`]).
pub fn hold_helper_to(core: Option<usize>) {
    if let Some(core) = core {
        hold_current_thread_to(core);
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;

    #[test]
    fn the_pin_setting_takes_on_and_off_words_and_nothing_else() {
        for off in ["0", "off", "OFF", " false ", "no"] {
            assert_eq!(parse_pin_setting(off), Some(false), "{off:?}");
        }
        for on in ["1", "on", "True", "yes\n"] {
            assert_eq!(parse_pin_setting(on), Some(true), "{on:?}");
        }
        for neither in ["", "2", "of", "00", "disable", "-1"] {
            assert_eq!(parse_pin_setting(neither), None, "{neither:?}");
        }
    }

    #[test]
    fn the_allowed_cores_are_distinct_and_at_least_the_standard_librarys_count() {
        let cores = allowed_cores();
        assert!(cores.windows(2).all(|w| w[0] < w[1]));
        // The standard library counts the same mask, less any cgroup quota.
        let available = std::thread::available_parallelism().map_or(1, |n| n.get());
        assert!(cores.len() >= available, "{cores:?} against {available}");
    }

    /// A thread held to one core reports that core as its mask, and the rest of the process
    /// keeps its own.
    #[test]
    fn a_held_thread_runs_on_its_core_only() {
        let cores = allowed_cores();
        let last = *cores.last().expect("at least one core");
        let (held, seen) = std::thread::spawn(move || {
            let held = hold_current_thread_to(last);
            (held && allowed_cores() == vec![last], current_core())
        })
        .join()
        .expect("the thread ends");
        assert!(held);
        assert_eq!(seen, Some(last));
        assert_eq!(allowed_cores(), cores);
    }
}
