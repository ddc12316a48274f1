//! `#` variables: numbered (`#5`, `#100`, Fanuc's locals, commons and LinuxCNC's numbered
//! parameters) and named (`#<depth>`, LinuxCNC). Scopes follow LinuxCNC's O-code reference:
//! inside an `o<…> call`, `#1`…`#30` are the call's own (its arguments, the rest 0, as rs274
//! sets them) and so is every named variable not starting with `_`; `M98` children share their
//! caller's variables, as on Fanuc controls.
//!
//! Reading a variable that was never set is an error naming it. That is stricter than either
//! controller (Fanuc reads it as *vacant*, LinuxCNC's numbered parameters start at 0 or at the
//! values of its parameter file): a verifier should not guess a value the program never gave.
//! System variables (Fanuc `#5001…`, LinuxCNC `#5220…`) are not modelled; they too are
//! undefined until the program sets them.

use std::collections::HashMap;

/// The highest variable number accepted.
pub const MAX_VARIABLE_NUMBER: u32 = 999_999;
/// The most distinct variables (numbered and named, all scopes) a program may set.
pub const MAX_VARIABLES: usize = 100_000;
/// Numbered variables local to an `o` call: `#1`…`#30` (LinuxCNC).
pub const CALL_LOCALS: u32 = 30;

/// Where a value is stored.
#[derive(Debug, Clone, PartialEq)]
pub enum Key {
    /// `#n`.
    Number(u32),
    /// `#<name>`, lower case.
    Name(Box<str>),
}

impl std::fmt::Display for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Key::Number(n) => write!(f, "#{n}"),
            Key::Name(s) => write!(f, "#<{s}>"),
        }
    }
}

/// The variables of one `o` call.
#[derive(Debug, Default)]
struct Scope {
    numbered: [f64; CALL_LOCALS as usize],
    named: HashMap<Box<str>, f64>,
}

/// All variables of a running program.
#[derive(Debug, Default)]
pub struct Variables {
    numbered: HashMap<u32, f64>,
    named: HashMap<Box<str>, f64>,
    /// One per active `o` call, innermost last.
    scopes: Vec<Scope>,
    /// Variables set so far in all scopes (bounded by [`MAX_VARIABLES`]).
    count: usize,
}

/// Too many variables.
#[derive(Debug, Clone, PartialEq)]
pub struct TooMany;

impl Variables {
    /// The value of `key`, if it was set.
    pub fn get(&self, key: &Key) -> Option<f64> {
        match key {
            Key::Number(n) => self.get_number(*n),
            Key::Name(name) => self.get_name(name),
        }
    }

    /// The value of `#n`, if it was set.
    pub fn get_number(&self, n: u32) -> Option<f64> {
        match self.scopes.last() {
            Some(s) if (1..=CALL_LOCALS).contains(&n) => Some(s.numbered[n as usize - 1]),
            _ => self.numbered.get(&n).copied(),
        }
    }

    /// The value of `#<name>`, if it was set.
    pub fn get_name(&self, name: &str) -> Option<f64> {
        match self.scopes.last() {
            Some(s) if !name.starts_with('_') => s.named.get(name).copied(),
            _ => self.named.get(name).copied(),
        }
    }

    /// Sets `key` to `value`.
    pub fn set(&mut self, key: &Key, value: f64) -> Result<(), TooMany> {
        let full = self.count >= MAX_VARIABLES;
        let inserted = match (key, self.scopes.last_mut()) {
            (Key::Number(n), Some(s)) if (1..=CALL_LOCALS).contains(n) => {
                s.numbered[*n as usize - 1] = value;
                false
            }
            (Key::Number(n), _) => {
                if full && !self.numbered.contains_key(n) {
                    return Err(TooMany);
                }
                self.numbered.insert(*n, value).is_none()
            }
            (Key::Name(name), Some(s)) if !name.starts_with('_') => {
                if full && !s.named.contains_key(name) {
                    return Err(TooMany);
                }
                s.named.insert(name.clone(), value).is_none()
            }
            (Key::Name(name), _) => {
                if full && !self.named.contains_key(name) {
                    return Err(TooMany);
                }
                self.named.insert(name.clone(), value).is_none()
            }
        };
        self.count += usize::from(inserted);
        Ok(())
    }

    /// Enters an `o` call with its arguments in `#1`, `#2`, …; the other locals are 0.
    pub fn enter(&mut self, args: &[f64]) {
        let mut scope = Scope::default();
        for (slot, &a) in scope.numbered.iter_mut().zip(args) {
            *slot = a;
        }
        self.scopes.push(scope);
    }

    /// Leaves the innermost `o` call, dropping its variables.
    pub fn leave(&mut self) {
        if let Some(s) = self.scopes.pop() {
            self.count = self.count.saturating_sub(s.named.len());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calls_have_their_own_locals_and_named_variables() {
        let mut v = Variables::default();
        let name = |s: &str| Key::Name(s.into());
        v.set(&Key::Number(1), 7.0).unwrap();
        v.set(&Key::Number(31), 6.0).unwrap();
        v.set(&name("depth"), 1.0).unwrap();
        v.enter(&[3.0]);
        assert_eq!(v.get_number(1), Some(3.0));
        assert_eq!(v.get_number(2), Some(0.0));
        assert_eq!(v.get_number(31), Some(6.0));
        assert_eq!(v.get(&name("depth")), None);
        v.set(&name("depth"), 2.0).unwrap();
        v.set(&name("_glob"), 5.0).unwrap();
        v.set(&Key::Number(2), 9.0).unwrap();
        v.leave();
        assert_eq!(v.get_number(1), Some(7.0));
        assert_eq!(v.get_number(2), None);
        assert_eq!(v.get(&name("depth")), Some(1.0));
        assert_eq!(v.get(&name("_glob")), Some(5.0));
    }

    #[test]
    fn the_number_of_variables_is_bounded() {
        let mut v = Variables::default();
        for n in 0..MAX_VARIABLES as u32 {
            v.set(&Key::Number(100 + n), 1.0).unwrap();
        }
        assert_eq!(v.set(&Key::Number(100), 2.0), Ok(()));
        assert_eq!(v.set(&Key::Number(99), 2.0), Err(TooMany));
    }
}
