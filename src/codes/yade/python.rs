//! A small, strict reader of the Python a YADE user writes (`millimpact deck`): its tokens,
//! its logical lines, the calls anywhere in them with their arguments as expressions, and the
//! numbers those expressions resolve to through literal values and module-level assignments.
//! Nothing is executed: a value that only the running script knows (a loop's variable, a
//! function's result, a name assigned inside a block) is unresolved, and says why.

use std::collections::HashMap;

use thiserror::Error;

/// One token of a Python source.
#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// A name.
    Name(String),
    /// An integer literal.
    Int(i64),
    /// A float literal (or an integer too large for `i64`).
    Float(f64),
    /// A string literal (adjacent literals are joined by the parser).
    Str(String),
    /// A formatted string literal (`f"…"`): its value is the running script's.
    FStr,
    /// An operator or a delimiter.
    Op(&'static str),
}

/// A token and the line (from 1) it starts on.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// The token.
    pub tok: Tok,
    /// Its line.
    pub line: usize,
    /// Its index in its statement (set when the statement is complete).
    pub pos: usize,
}

/// One logical line: a statement with its indentation and its source text.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    /// Its tokens.
    pub tokens: Vec<Token>,
    /// The line it starts on.
    pub line: usize,
    /// Its indentation (0: module level).
    pub indent: usize,
}

/// Python source the scanner cannot read (an unterminated string or bracket).
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("line {line}: {what}")]
pub struct ScanError {
    /// Where.
    pub line: usize,
    /// What.
    pub what: String,
}

const OPS3: [&str; 5] = ["**=", "//=", ">>=", "<<=", "..."];
const OPS2: [&str; 19] = [
    "**", "//", "==", "!=", "<=", ">=", "+=", "-=", "*=", "/=", "->", "%=", "&=", "|=", "^=", ":=",
    "<<", ">>", "@=",
];
const OPS1: &str = "()[]{},:;.=+-*/%<>&|^~@!";

fn op(s: &str) -> Option<&'static str> {
    OPS3.iter()
        .chain(OPS2.iter())
        .find(|o| **o == s)
        .copied()
        .or_else(|| {
            let c = s.chars().next()?;
            let at = OPS1.find(c)?;
            (s.len() == 1).then(|| &OPS1[at..at + 1])
        })
}

/// Split `source` into logical lines of tokens, as Python does: comments dropped, lines
/// joined inside brackets and after a backslash, `;` separating statements.
pub fn scan(source: &str) -> Result<Vec<Statement>, ScanError> {
    let chars: Vec<char> = source.chars().collect();
    let mut statements = Vec::new();
    let mut current: Vec<Token> = Vec::new();
    let mut start = (1, 0);
    let mut depth = 0usize;
    let mut line = 1;
    let mut at_line_start = true;
    let mut i = 0;
    let finish =
        |current: &mut Vec<Token>, statements: &mut Vec<Statement>, start: (usize, usize)| {
            if !current.is_empty() {
                for (k, t) in current.iter_mut().enumerate() {
                    t.pos = k;
                }
                statements.push(Statement {
                    tokens: std::mem::take(current),
                    line: start.0,
                    indent: start.1,
                });
            }
        };
    while i < chars.len() {
        let c = chars[i];
        if at_line_start && depth == 0 && current.is_empty() {
            let mut indent = 0;
            while i < chars.len() && (chars[i] == ' ' || chars[i] == '\t') {
                indent += 1;
                i += 1;
            }
            start = (line, indent);
            at_line_start = false;
            continue;
        }
        match c {
            '\n' => {
                line += 1;
                i += 1;
                if depth == 0 {
                    finish(&mut current, &mut statements, start);
                    at_line_start = true;
                }
            }
            ' ' | '\t' | '\r' | '\x0c' => i += 1,
            '#' => {
                while i < chars.len() && chars[i] != '\n' {
                    i += 1;
                }
            }
            '\\' if chars.get(i + 1) == Some(&'\n') => {
                line += 1;
                i += 2;
            }
            ';' if depth == 0 => {
                finish(&mut current, &mut statements, start);
                start = (line, start.1);
                i += 1;
            }
            _ if c.is_alphabetic() || c == '_' => {
                let begin = i;
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
                let word: String = chars[begin..i].iter().collect();
                let prefix = word.to_ascii_lowercase();
                let is_prefix =
                    ["r", "b", "u", "f", "rb", "br", "fr", "rf"].contains(&prefix.as_str());
                if is_prefix && matches!(chars.get(i), Some('\'' | '"')) {
                    let (tok, next, lines) = string(&chars, i, &prefix, line)?;
                    current.push(Token { tok, line, pos: 0 });
                    line += lines;
                    i = next;
                } else {
                    current.push(Token {
                        tok: Tok::Name(word),
                        line,
                        pos: 0,
                    });
                }
            }
            '\'' | '"' => {
                let (tok, next, lines) = string(&chars, i, "", line)?;
                current.push(Token { tok, line, pos: 0 });
                line += lines;
                i = next;
            }
            _ if c.is_ascii_digit()
                || (c == '.' && chars.get(i + 1).is_some_and(char::is_ascii_digit)) =>
            {
                let begin = i;
                let hex =
                    c == '0' && matches!(chars.get(i + 1), Some('x' | 'X' | 'o' | 'O' | 'b' | 'B'));
                while i < chars.len() {
                    let d = chars[i];
                    let exponent_sign =
                        (d == '+' || d == '-') && !hex && matches!(chars[i - 1], 'e' | 'E');
                    if d.is_ascii_alphanumeric() || d == '_' || d == '.' || exponent_sign {
                        i += 1;
                    } else {
                        break;
                    }
                }
                let text: String = chars[begin..i].iter().filter(|d| **d != '_').collect();
                let tok = number(&text).ok_or_else(|| ScanError {
                    line,
                    what: format!("number `{text}`"),
                })?;
                current.push(Token { tok, line, pos: 0 });
            }
            _ => {
                let three: String = chars[i..chars.len().min(i + 3)].iter().collect();
                let found = (1..=three.chars().count()).rev().find_map(|n| {
                    let s: String = three.chars().take(n).collect();
                    op(&s).map(|o| (o, n))
                });
                let Some((o, n)) = found else {
                    return Err(ScanError {
                        line,
                        what: format!("character `{c}`"),
                    });
                };
                match o {
                    "(" | "[" | "{" => depth += 1,
                    ")" | "]" | "}" => {
                        depth = depth.checked_sub(1).ok_or_else(|| ScanError {
                            line,
                            what: format!("`{o}` without its opening bracket"),
                        })?;
                    }
                    _ => {}
                }
                current.push(Token {
                    tok: Tok::Op(o),
                    line,
                    pos: 0,
                });
                i += n;
            }
        }
    }
    if depth > 0 {
        return Err(ScanError {
            line,
            what: "a bracket left open at the end of the file".into(),
        });
    }
    finish(&mut current, &mut statements, start);
    Ok(statements)
}

fn number(text: &str) -> Option<Tok> {
    let lower = text.to_ascii_lowercase();
    let radix = [("0x", 16), ("0o", 8), ("0b", 2)]
        .into_iter()
        .find(|(p, _)| lower.starts_with(p));
    if let Some((p, radix)) = radix {
        return i64::from_str_radix(&lower[p.len()..], radix)
            .ok()
            .map(Tok::Int);
    }
    if lower.ends_with('j') {
        return None;
    }
    if lower.chars().all(|c| c.is_ascii_digit()) {
        return Some(
            lower
                .parse::<i64>()
                .map_or_else(|_| Tok::Float(lower.parse().unwrap_or(f64::NAN)), Tok::Int),
        );
    }
    lower.parse::<f64>().ok().map(Tok::Float)
}

/// A string literal at `chars[i]` (the quote) with its prefix: the token, the index after it,
/// and the newlines it spans.
fn string(
    chars: &[char],
    i: usize,
    prefix: &str,
    line: usize,
) -> Result<(Tok, usize, usize), ScanError> {
    let quote = chars[i];
    let triple = chars.get(i + 1) == Some(&quote) && chars.get(i + 2) == Some(&quote);
    let raw = prefix.contains('r');
    let mut k = if triple { i + 3 } else { i + 1 };
    let mut value = String::new();
    let mut lines = 0;
    loop {
        let Some(&c) = chars.get(k) else {
            return Err(ScanError {
                line,
                what: "a string left open at the end of the file".into(),
            });
        };
        if c == '\n' {
            if !triple {
                return Err(ScanError {
                    line,
                    what: "a string left open at the end of its line".into(),
                });
            }
            lines += 1;
        }
        if c == '\\' {
            let next = chars.get(k + 1).copied().unwrap_or('\\');
            if next == '\n' {
                lines += 1;
            }
            if raw {
                value.push('\\');
                value.push(next);
            } else {
                value.push(match next {
                    'n' => '\n',
                    't' => '\t',
                    other => other,
                });
            }
            k += 2;
            continue;
        }
        if c == quote
            && (!triple || (chars.get(k + 1) == Some(&quote) && chars.get(k + 2) == Some(&quote)))
        {
            k += if triple { 3 } else { 1 };
            break;
        }
        value.push(c);
        k += 1;
    }
    let tok = if prefix.contains('f') {
        Tok::FStr
    } else {
        Tok::Str(value)
    };
    Ok((tok, k, lines))
}

/// A call: its callee as a dotted name and its arguments as written.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The callee (`utils.sphere`, `FrictMat`).
    pub func: String,
    /// Positional arguments.
    pub args: Vec<Expr>,
    /// Keyword arguments in the order written.
    pub kwargs: Vec<(String, Expr)>,
    /// The line of the callee.
    pub line: usize,
    /// Which statement (index) and token the call starts at: tells two calls on one line apart.
    pub at: (usize, usize),
}

impl Call {
    /// The last name of the callee (`sphere` for `utils.sphere`).
    pub fn name(&self) -> &str {
        self.func.rsplit('.').next().unwrap_or(&self.func)
    }

    /// The keyword argument `name`, else the positional argument at `position`.
    pub fn arg(&self, name: &str, position: Option<usize>) -> Option<&Expr> {
        self.kwargs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, e)| e)
            .or_else(|| position.and_then(|p| self.args.get(p)))
    }
}

/// An expression, as far as the reader reads one.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// An integer literal.
    Int(i64),
    /// A float literal.
    Float(f64),
    /// A string literal.
    Str(String),
    /// `True` or `False`.
    Bool(bool),
    /// `None`.
    NoneValue,
    /// A name, dotted (`math.pi`).
    Name(String),
    /// A call.
    Call(Call),
    /// A tuple or a list.
    Seq(Vec<Expr>),
    /// A unary `-` or `+`.
    Unary(&'static str, Box<Expr>),
    /// A binary arithmetic operation.
    Binary(&'static str, Box<Expr>, Box<Expr>),
    /// Anything else (a subscript, a comprehension, a comparison), as written.
    Opaque(String),
}

/// Source-like text of tokens, for messages.
pub fn text(tokens: &[Token]) -> String {
    let mut out = String::new();
    let mut previous: Option<&Tok> = None;
    for t in tokens {
        let glue = match (&previous, &t.tok) {
            (None, _) => false,
            (Some(Tok::Op("(" | "[" | "{" | ".")), _) => true,
            (_, Tok::Op(")" | "]" | "}" | "," | "." | "(" | "[" | ":")) => true,
            (Some(Tok::Op("-" | "+")), _) => false,
            _ => false,
        };
        if !glue && previous.is_some() {
            out.push(' ');
        }
        match &t.tok {
            Tok::Name(n) => out.push_str(n),
            Tok::Int(i) => out.push_str(&i.to_string()),
            Tok::Float(x) => out.push_str(&format!("{x:?}")),
            Tok::Str(s) => out.push_str(&format!("{s:?}")),
            Tok::FStr => out.push_str("f\"…\""),
            Tok::Op(o) => out.push_str(o),
        }
        previous = Some(&t.tok);
    }
    out
}

/// The index of the bracket that closes the one at `open`.
fn closing(tokens: &[Token], open: usize) -> Option<usize> {
    let mut depth = 0usize;
    for (k, t) in tokens.iter().enumerate().skip(open) {
        match t.tok {
            Tok::Op("(" | "[" | "{") => depth += 1,
            Tok::Op(")" | "]" | "}") => {
                depth -= 1;
                if depth == 0 {
                    return Some(k);
                }
            }
            _ => {}
        }
    }
    None
}

/// Split `tokens` at its top-level commas.
fn split_commas(tokens: &[Token]) -> Vec<&[Token]> {
    let mut parts = Vec::new();
    let mut depth = 0usize;
    let mut begin = 0;
    for (k, t) in tokens.iter().enumerate() {
        match t.tok {
            Tok::Op("(" | "[" | "{") => depth += 1,
            Tok::Op(")" | "]" | "}") => depth = depth.saturating_sub(1),
            Tok::Op(",") if depth == 0 => {
                parts.push(&tokens[begin..k]);
                begin = k + 1;
            }
            _ => {}
        }
    }
    if begin < tokens.len() {
        parts.push(&tokens[begin..]);
    }
    parts
}

/// The dotted name starting at `tokens[k]` and the index after it.
fn dotted(tokens: &[Token], mut k: usize) -> Option<(String, usize)> {
    let Tok::Name(first) = &tokens.get(k)?.tok else {
        return None;
    };
    let mut name = first.clone();
    k += 1;
    while let (Some(Tok::Op(".")), Some(Tok::Name(next))) = (
        tokens.get(k).map(|t| &t.tok),
        tokens.get(k + 1).map(|t| &t.tok),
    ) {
        name.push('.');
        name.push_str(next);
        k += 2;
    }
    Some((name, k))
}

/// Parse the call whose dotted callee starts at `tokens[k]` of statement `statement`, and the
/// index after its closing bracket.
fn call_at(tokens: &[Token], k: usize, statement: usize) -> Option<(Call, usize)> {
    let (func, open) = dotted(tokens, k)?;
    if tokens.get(open).map(|t| &t.tok) != Some(&Tok::Op("(")) {
        return None;
    }
    let close = closing(tokens, open)?;
    let mut call = Call {
        func,
        args: Vec::new(),
        kwargs: Vec::new(),
        line: tokens[k].line,
        at: (statement, tokens[k].pos),
    };
    for part in split_commas(&tokens[open + 1..close]) {
        if part.is_empty() {
            continue;
        }
        match (&part[0].tok, part.get(1).map(|t| &t.tok)) {
            (Tok::Name(key), Some(Tok::Op("="))) => call
                .kwargs
                .push((key.clone(), expression(&part[2..], statement))),
            _ => call.args.push(expression(part, statement)),
        }
    }
    Some((call, close + 1))
}

/// Every call in `statement` (the statement's index is `index`), nested ones included, in the
/// order they are written.
pub fn calls(statement: &Statement, index: usize) -> Vec<Call> {
    let tokens = &statement.tokens;
    let mut out = Vec::new();
    for k in 0..tokens.len() {
        let starts_chain = k == 0 || tokens[k - 1].tok != Tok::Op(".");
        if starts_chain
            && matches!(tokens[k].tok, Tok::Name(_))
            && let Some((call, _)) = call_at(tokens, k, index)
        {
            out.push(call);
        }
    }
    out
}

/// Parse `tokens` as an expression; what the reader does not read is [`Expr::Opaque`].
pub fn expression(tokens: &[Token], statement: usize) -> Expr {
    let mut parser = Parser {
        tokens,
        k: 0,
        statement,
    };
    match parser.sum() {
        Some(e) if parser.k == tokens.len() => e,
        _ => Expr::Opaque(text(tokens)),
    }
}

struct Parser<'a> {
    tokens: &'a [Token],
    k: usize,
    statement: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.tokens.get(self.k).map(|t| &t.tok)
    }

    fn binary(
        &mut self,
        ops: &[&'static str],
        next: fn(&mut Self) -> Option<Expr>,
    ) -> Option<Expr> {
        let mut left = next(self)?;
        while let Some(Tok::Op(o)) = self.peek() {
            let Some(o) = ops.iter().find(|x| *x == o).copied() else {
                break;
            };
            self.k += 1;
            let right = next(self)?;
            left = Expr::Binary(o, Box::new(left), Box::new(right));
        }
        Some(left)
    }

    fn sum(&mut self) -> Option<Expr> {
        self.binary(&["+", "-"], Self::product)
    }

    fn product(&mut self) -> Option<Expr> {
        self.binary(&["*", "/", "//", "%"], Self::unary)
    }

    fn unary(&mut self) -> Option<Expr> {
        match self.peek() {
            Some(Tok::Op(o @ ("-" | "+"))) => {
                let o: &'static str = o;
                self.k += 1;
                Some(Expr::Unary(o, Box::new(self.unary()?)))
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Option<Expr> {
        let base = self.atom()?;
        if self.peek() == Some(&Tok::Op("**")) {
            self.k += 1;
            // Right-associative, and binds tighter than a unary minus on its left.
            let exponent = self.unary()?;
            return Some(Expr::Binary("**", Box::new(base), Box::new(exponent)));
        }
        Some(base)
    }

    fn atom(&mut self) -> Option<Expr> {
        let token = self.tokens.get(self.k)?;
        let e = match &token.tok {
            Tok::Int(i) => {
                self.k += 1;
                Expr::Int(*i)
            }
            Tok::Float(x) => {
                self.k += 1;
                Expr::Float(*x)
            }
            Tok::Str(_) | Tok::FStr => {
                let mut joined = String::new();
                let mut formatted = false;
                while let Some(t) = self.peek() {
                    match t {
                        Tok::Str(s) => joined.push_str(s),
                        Tok::FStr => formatted = true,
                        _ => break,
                    }
                    self.k += 1;
                }
                if formatted {
                    return None;
                }
                Expr::Str(joined)
            }
            Tok::Name(n) if n == "True" || n == "False" => {
                self.k += 1;
                Expr::Bool(n == "True")
            }
            Tok::Name(n) if n == "None" => {
                self.k += 1;
                Expr::NoneValue
            }
            Tok::Name(_) => {
                if let Some((call, next)) = call_at(self.tokens, self.k, self.statement) {
                    self.k = next;
                    Expr::Call(call)
                } else {
                    let (name, next) = dotted(self.tokens, self.k)?;
                    self.k = next;
                    Expr::Name(name)
                }
            }
            Tok::Op(open @ ("(" | "[")) => {
                let close = closing(self.tokens, self.k)?;
                let inner = &self.tokens[self.k + 1..close];
                if inner
                    .iter()
                    .any(|t| matches!(&t.tok, Tok::Name(n) if n == "for"))
                {
                    return None;
                }
                let parts = split_commas(inner);
                let trailing_comma = inner.last().is_some_and(|t| t.tok == Tok::Op(","));
                let items: Vec<Expr> = parts
                    .iter()
                    .map(|p| expression(p, self.statement))
                    .collect();
                self.k = close + 1;
                if *open == "(" && items.len() == 1 && !trailing_comma {
                    items.into_iter().next()?
                } else {
                    Expr::Seq(items)
                }
            }
            _ => return None,
        };
        // A subscript or an attribute of a result: not read.
        if matches!(self.peek(), Some(Tok::Op("[" | "." | "("))) {
            return None;
        }
        Some(e)
    }
}

/// A value an expression resolves to.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// An integer.
    Int(i64),
    /// A float.
    Float(f64),
    /// A string.
    Str(String),
    /// A truth value.
    Bool(bool),
    /// `None`.
    NoneValue,
    /// A tuple, a list or a `Vector3`.
    Seq(Vec<Value>),
}

impl Value {
    /// The number, if it is one.
    pub fn number(&self) -> Option<f64> {
        match self {
            // Integers in a deck are small (ids, counts): exact as f64.
            #[allow(clippy::cast_precision_loss)]
            Value::Int(i) => Some(*i as f64),
            Value::Float(x) => Some(*x),
            _ => None,
        }
    }

    /// The value written as Python reads it back (floats exactly).
    pub fn python(&self) -> String {
        match self {
            Value::Int(i) => i.to_string(),
            Value::Float(x) => crate::codes::template::exact_number(*x),
            Value::Str(s) => format!("'{}'", s.replace('\\', "\\\\").replace('\'', "\\'")),
            Value::Bool(b) => if *b { "True" } else { "False" }.to_string(),
            Value::NoneValue => "None".to_string(),
            Value::Seq(items) => {
                let inner: Vec<String> = items.iter().map(Value::python).collect();
                if items.len() == 1 {
                    format!("({},)", inner[0])
                } else {
                    format!("({})", inner.join(", "))
                }
            }
        }
    }
}

/// Why an expression has no value the reader can give.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("{0}")]
pub struct Unresolved(pub String);

/// How a name is bound in the module.
#[derive(Clone, Debug, PartialEq)]
enum Binding {
    /// `NAME = EXPR` at module level, on its line.
    Assigned(usize, Expr),
    /// Bound some other way (in a block, by a loop, unpacked, augmented), on its line.
    Other(usize, &'static str),
}

/// The values a module gives its calls and names beyond literals: the reader's own knowledge
/// (the id `O.materials.append(…)` returns, what `PWaveTimeStep()` computes).
pub trait Known {
    /// The value of `call`, where the reader knows it.
    fn call(&self, call: &Call) -> Option<Result<Value, Unresolved>>;
}

/// A Python module as read: its statements and what its names are bound to.
#[derive(Clone, Debug)]
pub struct Module {
    /// The logical lines.
    pub statements: Vec<Statement>,
    bindings: HashMap<String, Vec<Binding>>,
    overrides: HashMap<String, Value>,
}

impl Module {
    /// Read `source`; `overrides` are names defined before it (from the command line), which
    /// replace the module's own assignments of them.
    pub fn read(source: &str, overrides: &[(String, String)]) -> Result<Self, ScanError> {
        let statements = scan(source)?;
        let mut bindings: HashMap<String, Vec<Binding>> = HashMap::new();
        for (index, s) in statements.iter().enumerate() {
            let t = &s.tokens;
            let name_at = |k: usize| match t.get(k).map(|x| &x.tok) {
                Some(Tok::Name(n)) => Some(n.clone()),
                _ => None,
            };
            let mut bind = |name: String, b: Binding| bindings.entry(name).or_default().push(b);
            match (name_at(0), t.get(1).map(|x| &x.tok)) {
                (Some(n), Some(Tok::Op("=")))
                    if s.indent == 0 && !["for", "if", "while"].contains(&n.as_str()) =>
                {
                    bind(n, Binding::Assigned(s.line, expression(&t[2..], index)));
                }
                (Some(n), Some(Tok::Op("="))) => {
                    bind(n, Binding::Other(s.line, "assigned inside a block"))
                }
                (Some(n), Some(Tok::Op(o))) if o.ends_with('=') && o.len() > 1 && *o != "==" => {
                    bind(n, Binding::Other(s.line, "changed in place"));
                }
                (Some(_), Some(Tok::Op(","))) => {
                    if let Some(eq) = t.iter().position(|x| x.tok == Tok::Op("=")) {
                        for part in split_commas(&t[..eq]) {
                            if let [
                                Token {
                                    tok: Tok::Name(m), ..
                                },
                            ] = part
                            {
                                bind(
                                    m.clone(),
                                    Binding::Other(s.line, "unpacked from a sequence"),
                                );
                            }
                        }
                    }
                }
                (Some(kw), _) if kw == "for" => {
                    let end = t
                        .iter()
                        .position(|x| x.tok == Tok::Name("in".into()))
                        .unwrap_or(t.len());
                    for x in &t[1..end] {
                        if let Tok::Name(m) = &x.tok {
                            bind(m.clone(), Binding::Other(s.line, "a loop's variable"));
                        }
                    }
                }
                (Some(kw), Some(Tok::Name(f))) if kw == "def" => {
                    bind(f.clone(), Binding::Other(s.line, "a function"));
                }
                _ => {}
            }
        }
        let overrides = overrides
            .iter()
            .map(|(n, v)| {
                let value = match number(v.trim()) {
                    Some(Tok::Int(i)) => Value::Int(i),
                    Some(Tok::Float(x)) => Value::Float(x),
                    _ => Value::Str(v.clone()),
                };
                (n.clone(), value)
            })
            .collect();
        Ok(Module {
            statements,
            bindings,
            overrides,
        })
    }

    /// Every call of the module with the index of its statement, in the order written.
    pub fn calls(&self) -> Vec<Call> {
        self.statements
            .iter()
            .enumerate()
            .flat_map(|(k, s)| calls(s, k))
            .collect()
    }

    /// The module-level expression `name` is bound to where line `line` uses it.
    pub fn binding(&self, name: &str, line: usize) -> Result<(usize, Expr), Unresolved> {
        let Some(all) = self.bindings.get(name) else {
            return Err(Unresolved(format!(
                "`{name}` is not assigned in the script"
            )));
        };
        if let Some(Binding::Other(at, how)) = all.iter().find(|b| matches!(b, Binding::Other(..)))
        {
            return Err(Unresolved(format!(
                "`{name}` is {how} (line {at}): its value is the running script's"
            )));
        }
        let before = all.iter().rev().find_map(|b| match b {
            Binding::Assigned(at, e) if *at < line => Some((*at, e.clone())),
            _ => None,
        });
        before.ok_or_else(|| Unresolved(format!("`{name}` is assigned only after line {line}")))
    }

    /// The value of `expr` written on line `line`.
    pub fn value(&self, expr: &Expr, line: usize, known: &dyn Known) -> Result<Value, Unresolved> {
        let num = |v: Value, what: &Expr| {
            v.number()
                .ok_or_else(|| Unresolved(format!("`{}` is not a number", show(what))))
        };
        Ok(match expr {
            Expr::Int(i) => Value::Int(*i),
            Expr::Float(x) => Value::Float(*x),
            Expr::Str(s) => Value::Str(s.clone()),
            Expr::Bool(b) => Value::Bool(*b),
            Expr::NoneValue => Value::NoneValue,
            Expr::Seq(items) => Value::Seq(
                items
                    .iter()
                    .map(|e| self.value(e, line, known))
                    .collect::<Result<_, _>>()?,
            ),
            Expr::Name(n) => {
                if let Some(v) = self.overrides.get(n) {
                    return Ok(v.clone());
                }
                match n.as_str() {
                    "math.pi" | "pi" | "numpy.pi" | "np.pi" => Value::Float(std::f64::consts::PI),
                    "math.e" => Value::Float(std::f64::consts::E),
                    "math.inf" | "inf" => Value::Float(f64::INFINITY),
                    _ if n.contains('.') => {
                        return Err(Unresolved(format!(
                            "`{n}` is an attribute the reader does not know"
                        )));
                    }
                    _ => {
                        // A name's value is resolved where it was assigned.
                        let (at, bound) = self.binding(n, line)?;
                        self.value(&bound, at, known)
                            .map_err(|e| Unresolved(format!("`{n}` (line {at}): {}", e.0)))?
                    }
                }
            }
            Expr::Unary(o, inner) => {
                let v = self.value(inner, line, known)?;
                match (o, v) {
                    (&"-", Value::Int(i)) => Value::Int(-i),
                    (&"+", Value::Int(i)) => Value::Int(i),
                    (o, v) => {
                        let x = num(v, inner)?;
                        Value::Float(if *o == "-" { -x } else { x })
                    }
                }
            }
            Expr::Binary(o, a, b) => {
                let (va, vb) = (self.value(a, line, known)?, self.value(b, line, known)?);
                if let (Value::Int(x), Value::Int(y)) = (&va, &vb) {
                    let exact = match *o {
                        "+" => x.checked_add(*y),
                        "-" => x.checked_sub(*y),
                        "*" => x.checked_mul(*y),
                        "//" if *y != 0 => Some(x.div_euclid(*y)),
                        "**" if (0..64).contains(y) => {
                            u32::try_from(*y).ok().and_then(|p| x.checked_pow(p))
                        }
                        _ => None,
                    };
                    if let Some(r) = exact {
                        return Ok(Value::Int(r));
                    }
                }
                let (x, y) = (num(va, a)?, num(vb, b)?);
                Value::Float(match *o {
                    "+" => x + y,
                    "-" => x - y,
                    "*" => x * y,
                    "/" => x / y,
                    "//" => (x / y).floor(),
                    "%" => x - y * (x / y).floor(),
                    _ => x.powf(y),
                })
            }
            Expr::Call(c) => {
                if let Some(v) = known.call(c) {
                    return v;
                }
                let args = c
                    .args
                    .iter()
                    .map(|e| self.value(e, line, known))
                    .collect::<Result<Vec<_>, _>>()?;
                let f = |k: usize| {
                    args.get(k)
                        .and_then(Value::number)
                        .ok_or_else(|| Unresolved(format!("`{}` takes a number", c.func)))
                };
                let name = c
                    .func
                    .trim_start_matches("math.")
                    .trim_start_matches("numpy.")
                    .trim_start_matches("np.");
                if !c.kwargs.is_empty() && name != "Vector3" {
                    return Err(Unresolved(format!(
                        "`{}(…)` with keywords is not read",
                        c.func
                    )));
                }
                match name {
                    "sqrt" => Value::Float(f(0)?.sqrt()),
                    "radians" => Value::Float(f(0)?.to_radians()),
                    "degrees" => Value::Float(f(0)?.to_degrees()),
                    "exp" => Value::Float(f(0)?.exp()),
                    "log" if args.len() == 1 => Value::Float(f(0)?.ln()),
                    "log10" => Value::Float(f(0)?.log10()),
                    "sin" => Value::Float(f(0)?.sin()),
                    "cos" => Value::Float(f(0)?.cos()),
                    "tan" => Value::Float(f(0)?.tan()),
                    "atan" => Value::Float(f(0)?.atan()),
                    "pow" => Value::Float(f(0)?.powf(f(1)?)),
                    "abs" | "fabs" => match &args[..] {
                        [Value::Int(i)] => Value::Int(i.abs()),
                        _ => Value::Float(f(0)?.abs()),
                    },
                    "float" => Value::Float(f(0)?),
                    "min" | "max" if !args.is_empty() => {
                        let xs = (0..args.len()).map(f).collect::<Result<Vec<_>, _>>()?;
                        let pick = if name == "min" { f64::min } else { f64::max };
                        Value::Float(xs.into_iter().reduce(pick).unwrap_or(f64::NAN))
                    }
                    "Vector3" | "Vector3r" if c.kwargs.is_empty() => Value::Seq(args),
                    _ => {
                        return Err(Unresolved(format!(
                            "`{}(…)` is a call whose result is the running script's",
                            c.func
                        )));
                    }
                }
            }
            Expr::Opaque(t) => {
                return Err(Unresolved(format!(
                    "`{t}` is not read (a literal, a name assigned a number at module level, or arithmetic of them is)"
                )));
            }
        })
    }
}

/// An expression written back, for messages.
pub fn show(expr: &Expr) -> String {
    match expr {
        Expr::Int(i) => i.to_string(),
        Expr::Float(x) => format!("{x:?}"),
        Expr::Str(s) => format!("'{s}'"),
        Expr::Bool(b) => if *b { "True" } else { "False" }.into(),
        Expr::NoneValue => "None".into(),
        Expr::Name(n) => n.clone(),
        Expr::Call(c) => {
            let mut parts: Vec<String> = c.args.iter().map(show).collect();
            parts.extend(c.kwargs.iter().map(|(k, v)| format!("{k}={}", show(v))));
            format!("{}({})", c.func, parts.join(", "))
        }
        Expr::Seq(items) => format!(
            "({})",
            items.iter().map(show).collect::<Vec<_>>().join(", ")
        ),
        Expr::Unary(o, e) => format!("{o}{}", show(e)),
        Expr::Binary(o, a, b) => format!("{} {o} {}", show(a), show(b)),
        Expr::Opaque(t) => t.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Nothing;
    impl Known for Nothing {
        fn call(&self, _: &Call) -> Option<Result<Value, Unresolved>> {
            None
        }
    }

    #[test]
    fn logical_lines_join_brackets_and_continuations_and_drop_comments() {
        let s = scan("a = (1 +\n  2)  # c\nb = 3 \\\n + 4; c = 'x#y'\n\ndef f():\n    d = 1\n")
            .unwrap();
        let lines: Vec<(usize, usize)> = s.iter().map(|x| (x.line, x.indent)).collect();
        assert_eq!(lines, [(1, 0), (3, 0), (4, 0), (6, 0), (7, 4)]);
        assert_eq!(s[2].tokens[2].tok, Tok::Str("x#y".into()));
    }

    #[test]
    fn module_level_numbers_resolve_and_others_say_why() {
        let m = Module::read(
            "import math\nR = 0.03\nr = R / 2\nE = 2e11\nphi = math.radians(30)\nfor i in range(3):\n    k = i\nn = 2 ** 3\nq = -2**2\n",
            &[],
        )
        .unwrap();
        let v = |src: &str| {
            let s = scan(src).unwrap();
            m.value(&expression(&s[0].tokens, 0), 100, &Nothing)
        };
        assert_eq!(v("r * 4").unwrap(), Value::Float(0.06));
        assert_eq!(v("phi").unwrap(), Value::Float(30f64.to_radians()));
        assert_eq!(v("n").unwrap(), Value::Int(8));
        assert_eq!(v("q").unwrap(), Value::Int(-4));
        assert_eq!(
            v("(1, E)").unwrap(),
            Value::Seq(vec![Value::Int(1), Value::Float(2e11)])
        );
        let e = v("k").unwrap_err().0;
        assert!(e.contains("assigned inside a block (line 7)"), "{e}");
        let e = v("i").unwrap_err().0;
        assert!(e.contains("a loop's variable"), "{e}");
        let e = v("random.random()").unwrap_err().0;
        assert!(e.contains("running script's"), "{e}");
        let e = m.value(&Expr::Name("R".into()), 2, &Nothing).unwrap_err().0;
        assert!(e.contains("only after line 2"), "{e}");
    }

    #[test]
    fn calls_are_found_nested_with_their_arguments() {
        let s = scan("O.bodies.append([utils.sphere((0, 0, 1), 0.01, material='steel') for i in range(3)])\n").unwrap();
        let found = calls(&s[0], 0);
        let names: Vec<&str> = found.iter().map(|c| c.func.as_str()).collect();
        assert_eq!(names, ["O.bodies.append", "utils.sphere", "range"]);
        let sphere = &found[1];
        assert_eq!(sphere.arg("radius", Some(1)), Some(&Expr::Float(0.01)));
        assert_eq!(
            sphere.arg("material", Some(7)),
            Some(&Expr::Str("steel".into()))
        );
        assert!(matches!(found[0].args[0], Expr::Opaque(_)));
    }

    #[test]
    fn values_are_written_back_as_python_reads_them() {
        let v = Value::Seq(vec![
            Value::Int(1),
            Value::Float(0.1),
            Value::Str("it's".into()),
            Value::Bool(true),
        ]);
        assert_eq!(v.python(), "(1, 1e-1, 'it\\'s', True)");
    }
}
