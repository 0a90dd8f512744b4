//! A millimpact command line that reproduces a figure or a table, built from its parts and
//! rendered one way everywhere it is printed or stored.

use std::fmt;

use serde::{Serialize, Serializer};

/// `millimpact <command> <arguments…>`: positional arguments and options in the order given.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Invocation {
    words: Vec<String>,
}

impl Invocation {
    /// `millimpact command`.
    pub(crate) fn new(command: &str) -> Invocation {
        Invocation {
            words: vec!["millimpact".into(), command.into()],
        }
    }

    /// A positional argument (a case file, a sweep file).
    pub(crate) fn arg(mut self, value: impl fmt::Display) -> Invocation {
        self.words.push(value.to_string());
        self
    }

    /// Positional arguments, in order.
    pub(crate) fn args<T: fmt::Display>(self, values: impl IntoIterator<Item = T>) -> Invocation {
        values.into_iter().fold(self, Invocation::arg)
    }

    /// `--name value`.
    pub(crate) fn option(mut self, name: &'static str, value: impl fmt::Display) -> Invocation {
        self.words.push(name.into());
        self.words.push(value.to_string());
        self
    }

    /// `--name value` where there is a value.
    pub(crate) fn option_if<T: fmt::Display>(
        self,
        name: &'static str,
        value: Option<T>,
    ) -> Invocation {
        match value {
            Some(v) => self.option(name, v),
            None => self,
        }
    }

    /// `--name` where `on`.
    pub(crate) fn flag(mut self, name: &'static str, on: bool) -> Invocation {
        if on {
            self.words.push(name.into());
        }
        self
    }
}

impl fmt::Display for Invocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.words.join(" "))
    }
}

/// Stored and exported as the command line it renders.
impl Serialize for Invocation {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_invocation_renders_its_parts_in_order() {
        let command = Invocation::new("compare")
            .args(["cases/a.toml", "cases/b.toml"])
            .option("--format", "csv")
            .option_if("--timestep", None::<f64>)
            .flag("--live", true)
            .flag("--clamp", false);
        assert_eq!(
            command.to_string(),
            "millimpact compare cases/a.toml cases/b.toml --format csv --live"
        );
        assert_eq!(
            serde_json::to_string(&command).unwrap(),
            "\"millimpact compare cases/a.toml cases/b.toml --format csv --live\""
        );
    }
}
