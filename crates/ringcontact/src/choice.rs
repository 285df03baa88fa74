//! A closed list of named options (a punch shape, a method, a far-field treatment): the names a
//! command line, a scene file or JSON spells, each with one line on what it is. A program builds
//! its flags from [`Choice::ALL`]; the library depends on no command-line crate.

/// One of a closed list of named options.
pub trait Choice: Copy + Send + Sync + 'static {
    /// Every option, in the order a listing shows them.
    const ALL: &'static [Self];

    /// The option's name (`ring-bem`), as the command line and JSON spell it.
    fn name(self) -> &'static str;

    /// One line on what the option is, for a program's help.
    fn description(self) -> &'static str;

    /// The option named `name`, if there is one.
    fn named(name: &str) -> Option<Self> {
        Self::ALL
            .iter()
            .copied()
            .find(|option| option.name() == name)
    }

    /// Every name, joined by `separator`.
    fn names_joined(separator: &str) -> String {
        Self::ALL
            .iter()
            .map(|option| option.name())
            .collect::<Vec<_>>()
            .join(separator)
    }
}
