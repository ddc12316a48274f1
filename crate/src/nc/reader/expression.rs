//! Expressions: numbers, `#` variables and bracketed arithmetic, evaluated as LinuxCNC's
//! interpreter does (`interp_execute.cc`, `execute_binary1/2`, `execute_unary`; precedence from
//! `interp_read.cc`, `precedence`): `**` binds tightest, then `*` `/` `MOD`, then `+` `-`, then
//! the comparisons `EQ NE GT GE LT LE` (EQ, NE, GE, LE within 1e-4, LinuxCNC's
//! `TOLERANCE_EQUAL`), then `AND OR XOR` (0 is false, anything else true; the result 0 or 1);
//! operators of one level associate to the left. `MOD` gives a result ≥ 0 (LinuxCNC's rule).
//! Functions take and give degrees: `SIN COS TAN ASIN ACOS ATAN ABS SQRT EXP LN FIX` (floor)
//! `FUP` (ceiling) `ROUND` (half away from zero) and `EXISTS[#<name>]`; `ATAN[a]/[b]` (LinuxCNC,
//! Fanuc) and `ATAN[a,b]` (later Fanuc controls) are the angle of the point (b, a), and
//! `POW[a,b]` (Fanuc) is a to the power b.
//!
//! Where a value may stand: after a word letter, an unbracketed number, variable, function or
//! `[…]`, with any signs before it; the Fanuc-style controllers also take the symbolic
//! operators without brackets (`z0+0.1`, a lab program's approach block), and so does this
//! reader (`X1-2` is X −1; no standard program writes that otherwise). The right side of a
//! setting `#8 = #8 - #103` is a whole expression, keyword operators included (Fanuc), where
//! LinuxCNC wants brackets. Every result must be finite. Bracket and function nesting is bounded
//! ([`MAX_DEPTH`]), so no line can drive the evaluator deep.

use super::error::Problem;
use super::lexer::Cursor;
use super::variables::{Key, MAX_VARIABLE_NUMBER, Variables};

/// Deepest nesting of brackets and functions in one expression.
pub const MAX_DEPTH: usize = 32;

/// Longest name of a `#<name>` variable (LinuxCNC's lines are 255 characters).
pub const MAX_NAME: usize = 255;

/// LinuxCNC's `TOLERANCE_EQUAL`: EQ, NE, LE and GE treat values this close as equal.
const TOLERANCE_EQUAL: f64 = 1e-4;

/// Which operators may join operands without brackets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Context {
    /// A word's value: `+ - * / **` only (a letter starts the next word).
    Word,
    /// Inside brackets or on the right of `=`: every operator.
    Full,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor,
}

impl Op {
    fn precedence(self) -> u8 {
        match self {
            Op::Pow => 6,
            Op::Mul | Op::Div | Op::Mod => 5,
            Op::Add | Op::Sub => 4,
            Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => 3,
            Op::And | Op::Or | Op::Xor => 2,
        }
    }

    fn apply(self, a: f64, b: f64) -> Result<f64, Problem> {
        let truth = |t: bool| if t { 1.0 } else { 0.0 };
        let near = (a - b).abs() < TOLERANCE_EQUAL;
        Ok(match self {
            Op::Pow => {
                if a < 0.0 && b.floor() != b {
                    return Err(Problem::Arithmetic(format!(
                        "{a} ** {b}: a negative number to a non-integer power"
                    )));
                }
                a.powf(b)
            }
            Op::Mul => a * b,
            Op::Div => {
                if b == 0.0 {
                    return Err(Problem::Arithmetic(format!("{a} / 0: division by zero")));
                }
                a / b
            }
            Op::Mod => {
                if b == 0.0 {
                    return Err(Problem::Arithmetic(format!("{a} MOD 0")));
                }
                let r = a % b;
                if r < 0.0 { r + b.abs() } else { r }
            }
            Op::Add => a + b,
            Op::Sub => a - b,
            Op::Eq => truth(near),
            Op::Ne => truth(!near),
            Op::Gt => truth(a > b),
            Op::Ge => truth(near || a >= b),
            Op::Lt => truth(a < b),
            Op::Le => truth(near || a <= b),
            Op::And => truth(a != 0.0 && b != 0.0),
            Op::Or => truth(a != 0.0 || b != 0.0),
            Op::Xor => truth((a != 0.0) != (b != 0.0)),
        })
    }
}

/// Keyword operators, as they appear in a lowered, space-free line.
const KEYWORD_OPS: [(&[u8], Op); 10] = [
    (b"mod", Op::Mod),
    (b"eq", Op::Eq),
    (b"ne", Op::Ne),
    (b"gt", Op::Gt),
    (b"ge", Op::Ge),
    (b"lt", Op::Lt),
    (b"le", Op::Le),
    (b"and", Op::And),
    (b"or", Op::Or),
    (b"xor", Op::Xor),
];

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Func {
    Abs,
    Acos,
    Asin,
    Atan,
    Cos,
    Exp,
    Exists,
    Fix,
    Fup,
    Ln,
    Pow,
    Round,
    Sin,
    Sqrt,
    Tan,
}

/// Function names, each followed by `[` in the text.
const FUNCS: [(&[u8], Func); 15] = [
    (b"abs[", Func::Abs),
    (b"acos[", Func::Acos),
    (b"asin[", Func::Asin),
    (b"atan[", Func::Atan),
    (b"cos[", Func::Cos),
    (b"exp[", Func::Exp),
    (b"exists[", Func::Exists),
    (b"fix[", Func::Fix),
    (b"fup[", Func::Fup),
    (b"ln[", Func::Ln),
    (b"pow[", Func::Pow),
    (b"round[", Func::Round),
    (b"sin[", Func::Sin),
    (b"sqrt[", Func::Sqrt),
    (b"tan[", Func::Tan),
];

/// Evaluates expressions of one line against the variables.
pub struct Evaluator<'v> {
    vars: &'v Variables,
    depth: usize,
}

impl<'v> Evaluator<'v> {
    /// An evaluator reading `vars`.
    pub fn new(vars: &'v Variables) -> Self {
        Self { vars, depth: 0 }
    }

    /// An expression at the cursor: operands joined by the operators `ctx` allows.
    pub fn expression(&mut self, c: &mut Cursor, ctx: Context) -> Result<f64, Problem> {
        let first = self.operand(c)?;
        let Some(mut op) = operator(c, ctx) else {
            return Ok(first);
        };
        // Precedence climbing with a fixed stack: pending operators have strictly rising
        // precedence (five levels), so at most five wait at once.
        let mut values = [0.0f64; 6];
        let mut ops = [Op::Add; 5];
        values[0] = first;
        let mut n = 0usize;
        loop {
            while n > 0 && ops[n - 1].precedence() >= op.precedence() {
                values[n - 1] = finite(ops[n - 1].apply(values[n - 1], values[n])?)?;
                n -= 1;
            }
            ops[n] = op;
            n += 1;
            values[n] = self.operand(c)?;
            match operator(c, ctx) {
                Some(next) => op = next,
                None => break,
            }
        }
        while n > 0 {
            values[n - 1] = finite(ops[n - 1].apply(values[n - 1], values[n])?)?;
            n -= 1;
        }
        Ok(values[0])
    }

    /// One operand with its signs: a number, `#…`, `[…]` or a function.
    pub fn operand(&mut self, c: &mut Cursor) -> Result<f64, Problem> {
        let mut sign = 1.0;
        loop {
            if c.eat(b'-') {
                sign = -sign;
            } else if !c.eat(b'+') {
                break;
            }
        }
        let v = match c.peek() {
            Some(b'0'..=b'9' | b'.') => c
                .number()
                .ok_or_else(|| Problem::Syntax(format!("bad number at `{}`", c.rest())))?,
            Some(b'#') => {
                let key = self.key(c)?;
                self.vars
                    .get(&key)
                    .ok_or_else(|| Problem::Undefined(key.to_string()))?
            }
            Some(b'[') => self.bracket(c)?,
            Some(_) => self.function(c)?,
            None => return Err(Problem::Syntax("a value is missing at the end".into())),
        };
        finite(sign * v)
    }

    /// The variable named at the cursor (`#5`, `#<name>`, `#[expr]`, `##1`).
    pub fn key(&mut self, c: &mut Cursor) -> Result<Key, Problem> {
        let start = c.i;
        if !c.eat(b'#') {
            return Err(Problem::Syntax(format!(
                "expected `#`, found `{}`",
                c.rest()
            )));
        }
        if c.eat(b'<') {
            let from = c.i;
            let len = c.s[from..]
                .iter()
                .position(|&b| b == b'>')
                .ok_or_else(|| Problem::Syntax("a #<name> has no closing `>`".into()))?;
            c.i = from + len + 1;
            let name = c.since(from);
            let name = &name[..name.len() - 1];
            if name.is_empty() || name.len() > MAX_NAME {
                return Err(Problem::Syntax(format!(
                    "a #<name> has 1 to {MAX_NAME} characters, not {}",
                    name.len()
                )));
            }
            return Ok(Key::Name(name.into()));
        }
        let n = self.enter(|e| e.operand(c))?;
        let r = n.round();
        if (n - r).abs() > TOLERANCE_EQUAL || !(1.0..=f64::from(MAX_VARIABLE_NUMBER)).contains(&r) {
            return Err(Problem::Syntax(format!(
                "`{}`: a variable number must be a whole number from 1 to {MAX_VARIABLE_NUMBER}, \
                 not {n}",
                c.since(start)
            )));
        }
        Ok(Key::Number(r as u32))
    }

    fn bracket(&mut self, c: &mut Cursor) -> Result<f64, Problem> {
        c.eat(b'[');
        let v = self.enter(|e| e.expression(c, Context::Full))?;
        close(c)?;
        Ok(v)
    }

    fn function(&mut self, c: &mut Cursor) -> Result<f64, Problem> {
        let Some(&(name, f)) = FUNCS.iter().find(|(name, _)| c.at_keyword(name)) else {
            return Err(Problem::Syntax(format!(
                "expected a value (number, #variable, [expression] or function), found `{}`",
                c.rest()
            )));
        };
        c.i += name.len();
        if f == Func::Exists {
            let key = self.key(c)?;
            close(c)?;
            return Ok(if self.vars.get(&key).is_some() {
                1.0
            } else {
                0.0
            });
        }
        let a = self.enter(|e| e.expression(c, Context::Full))?;
        let second = if c.eat(b',') {
            Some(self.enter(|e| e.expression(c, Context::Full))?)
        } else {
            None
        };
        close(c)?;
        let name = std::str::from_utf8(&name[..name.len() - 1]).unwrap_or("?");
        let domain = |ok: bool, why: &str| {
            if ok {
                Ok(())
            } else {
                Err(Problem::Arithmetic(format!("{name}[{a}]: {why}")))
            }
        };
        let v = match (f, second) {
            (Func::Atan, Some(b)) => a.atan2(b).to_degrees(),
            (Func::Atan, None) => {
                // LinuxCNC and Fanuc: ATAN[a]/[b].
                if !c.eat(b'/') || c.peek() != Some(b'[') {
                    return Err(Problem::Syntax(format!(
                        "ATAN needs ATAN[a]/[b] or ATAN[a,b], found `{}`",
                        c.rest()
                    )));
                }
                let b = self.bracket(c)?;
                a.atan2(b).to_degrees()
            }
            (Func::Pow, Some(b)) => Op::Pow.apply(a, b)?,
            (_, Some(_)) | (Func::Pow, None) => {
                return Err(Problem::Syntax(format!(
                    "{name} takes {} argument(s)",
                    if f == Func::Pow { 2 } else { 1 }
                )));
            }
            (Func::Abs, None) => a.abs(),
            (Func::Acos, None) => {
                domain((-1.0..=1.0).contains(&a), "outside [-1, 1]")?;
                a.acos().to_degrees()
            }
            (Func::Asin, None) => {
                domain((-1.0..=1.0).contains(&a), "outside [-1, 1]")?;
                a.asin().to_degrees()
            }
            (Func::Cos, None) => a.to_radians().cos(),
            (Func::Sin, None) => a.to_radians().sin(),
            (Func::Tan, None) => a.to_radians().tan(),
            (Func::Exp, None) => a.exp(),
            (Func::Fix, None) => a.floor(),
            (Func::Fup, None) => a.ceil(),
            (Func::Ln, None) => {
                domain(a > 0.0, "not positive")?;
                a.ln()
            }
            (Func::Round, None) => a.round(),
            (Func::Sqrt, None) => {
                domain(a >= 0.0, "negative")?;
                a.sqrt()
            }
            (Func::Exists, None) => unreachable!("handled above"),
        };
        finite(v)
    }

    /// Runs `f` one nesting level deeper, refusing past [`MAX_DEPTH`].
    fn enter<T>(&mut self, f: impl FnOnce(&mut Self) -> Result<T, Problem>) -> Result<T, Problem> {
        if self.depth >= MAX_DEPTH {
            return Err(Problem::Limit {
                what: "expression nesting".into(),
                limit: MAX_DEPTH as u64,
                hint: "brackets, functions and indirect # nested deeper than this".into(),
            });
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }
}

fn operator(c: &mut Cursor, ctx: Context) -> Option<Op> {
    let op = match (c.peek()?, c.peek2()) {
        (b'*', Some(b'*')) => Some((Op::Pow, 2)),
        (b'*', _) => Some((Op::Mul, 1)),
        (b'/', _) => Some((Op::Div, 1)),
        (b'+', _) => Some((Op::Add, 1)),
        (b'-', _) => Some((Op::Sub, 1)),
        _ if ctx == Context::Full => KEYWORD_OPS
            .iter()
            .find(|(w, _)| c.at_keyword(w))
            .map(|&(w, op)| (op, w.len())),
        _ => None,
    };
    let (op, len) = op?;
    c.i += len;
    Some(op)
}

fn close(c: &mut Cursor) -> Result<(), Problem> {
    if c.eat(b']') {
        Ok(())
    } else if c.done() {
        Err(Problem::Syntax("a `[` is not closed".into()))
    } else {
        Err(Problem::Syntax(format!(
            "expected `]`, found `{}`",
            c.rest()
        )))
    }
}

fn finite(v: f64) -> Result<f64, Problem> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Problem::Arithmetic(format!("the result is {v}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval_with(vars: &Variables, s: &str, ctx: Context) -> Result<f64, Problem> {
        let mut c = Cursor::new(s.as_bytes());
        let v = Evaluator::new(vars).expression(&mut c, ctx)?;
        assert!(c.done(), "{s}: left `{}`", c.rest());
        Ok(v)
    }

    fn eval(s: &str) -> f64 {
        eval_with(&Variables::default(), s, Context::Full).unwrap()
    }

    /// Values rs274 (LinuxCNC 2.9) prints for the same expressions (see the module docs).
    #[test]
    fn operators_and_functions_match_linuxcnc() {
        assert_eq!(eval("1+2*3**2"), 19.0);
        assert_eq!(eval("5-3-1"), 1.0);
        assert_eq!(eval("2**3**2"), 64.0);
        assert_eq!(eval("3mod-2"), 1.0);
        assert_eq!(eval("-3mod2"), 1.0);
        assert_eq!(eval("[1eq1.00005]"), 1.0);
        assert_eq!(eval("[1eq1.0002]"), 0.0);
        assert_eq!(eval("round[-2.5]"), -3.0);
        assert_eq!(eval("fix[-2.5]"), -3.0);
        assert_eq!(eval("fup[-2.5]"), -2.0);
        assert_eq!(eval("atan[1]/[1]"), 45.0);
        assert_eq!(eval("atan[1,-1]"), 135.0);
        assert!((eval("sin[30]") - 0.5).abs() < 1e-15);
        assert!((eval("cos[60]") - 0.5).abs() < 1e-15);
        assert!((eval("acos[0.5]") - 60.0).abs() < 1e-12);
        assert_eq!(eval("sqrt[16]+abs[-2]"), 6.0);
        assert_eq!(eval("pow[2,10]"), 1024.0);
        assert_eq!(eval("1lt2and2gt1"), 1.0);
        assert_eq!(eval("[1lt2]xor[2lt3]"), 0.0);
        assert_eq!(eval("--2"), 2.0);
        assert_eq!(eval("-[2+3]*2"), -10.0);
    }

    #[test]
    fn variables_are_read_and_undefined_ones_refused() {
        let mut vars = Variables::default();
        vars.set(&Key::Number(8), -0.25).unwrap();
        vars.set(&Key::Number(103), 0.01).unwrap();
        vars.set(&Key::Number(1), 8.0).unwrap();
        vars.set(&Key::Name("depth".into()), 2.0).unwrap();
        let v = |s: &str| eval_with(&vars, s, Context::Full);
        assert_eq!(v("#8-#103").unwrap(), -0.26);
        assert_eq!(v("##1").unwrap(), -0.25);
        assert_eq!(v("#[4+4]").unwrap(), -0.25);
        assert_eq!(v("#<depth>*2").unwrap(), 4.0);
        assert_eq!(v("exists[#<depth>]+exists[#<nope>]").unwrap(), 1.0);
        assert_eq!(v("#9").unwrap_err(), Problem::Undefined("#9".into()));
        assert_eq!(
            v("#<nope>").unwrap_err(),
            Problem::Undefined("#<nope>".into())
        );
        assert!(matches!(v("#1.5"), Err(Problem::Syntax(_))));
        assert!(matches!(v("#0"), Err(Problem::Syntax(_))));
    }

    #[test]
    fn word_values_stop_at_the_next_letter() {
        let vars = Variables::default();
        let mut c = Cursor::new(b"0+0.1f20");
        let mut e = Evaluator::new(&vars);
        assert_eq!(e.expression(&mut c, Context::Word).unwrap(), 0.1);
        assert_eq!(c.rest(), "f20");
        let mut c = Cursor::new(b"5mod2");
        assert_eq!(e.expression(&mut c, Context::Word).unwrap(), 5.0);
        assert_eq!(c.rest(), "mod2");
    }

    #[test]
    fn bad_arithmetic_and_deep_nesting_are_refused() {
        let vars = Variables::default();
        let v = |s: &str| eval_with(&vars, s, Context::Full);
        for bad in [
            "1/0",
            "sqrt[-1]",
            "ln[0]",
            "asin[2]",
            "[-8]**0.5",
            "exp[1000]",
            "99999999999999999999999999999999999999999**99",
        ] {
            assert!(matches!(v(bad), Err(Problem::Arithmetic(_))), "{bad}");
        }
        for bad in ["[1+2", "1+", "abs[1,2]", "atan[1]", "foo[1]", "1+]"] {
            assert!(v(bad).is_err(), "{bad}");
        }
        let deep = format!(
            "{}1{}",
            "[".repeat(MAX_DEPTH + 1),
            "]".repeat(MAX_DEPTH + 1)
        );
        assert!(matches!(v(&deep), Err(Problem::Limit { .. })));
        let ok = format!(
            "{}1{}",
            "[".repeat(MAX_DEPTH - 1),
            "]".repeat(MAX_DEPTH - 1)
        );
        assert_eq!(v(&ok).unwrap(), 1.0);
    }
}
