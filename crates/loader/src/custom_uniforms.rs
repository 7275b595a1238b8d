//! Custom uniforms and variables of `shaders.properties`, evaluated for one frame:
//!
//! ```text
//! uniform.<float|int|bool|vec2|vec3|vec4>.<name>=<expression>
//! variable.<float|int|bool|vec2|vec3|vec4>.<name>=<expression>
//! ```
//!
//! Semantics follow OptiFine's documentation (OptiFineDoc/doc/shaders.properties, "Custom
//! uniforms") and Iris's (the custom uniforms page of its shaders.properties reference and its
//! function table), summarised here in our own words:
//!
//! * Definitions are evaluated in file order; a definition sees the standard uniforms and every
//!   custom variable or uniform defined above it. Uniforms are sent to the shaders, variables
//!   only feed other definitions.
//! * Numbers are floats, as in OptiFine (an `int` standard uniform such as `worldTime` is read
//!   as its value). Evaluation is in f64; the harness uploads f32. Booleans are a separate type:
//!   `!`, `&&`, `||`, `if()` conditions want bools, arithmetic wants numbers.
//! * Operators, loosest first: `||`; `&&`; `==` `!=`; `<` `<=` `>` `>=`; `+` `-`; `*` `/` `%`;
//!   unary `-` `!`. Binary operators associate to the left. `%` is the remainder with the sign
//!   of the dividend (Java's `%`), `fmod` is the floored one.
//! * A component is read with a suffix on a name: `sunPosition.y`, `skyColor.r`, Iris's
//!   `.w/.a`, `.s/.t/.p/.q` and `.0`–`.3`; a matrix element with two: `gbufferModelView.3.1`
//!   is column 3, row 1, GLSL's `m[3][1]`, as Iris reads it (its first suffix picks a column).
//!   OptiFine's text calls the indices "row and column"; its code is not public, so Iris's
//!   reading is the one followed.
//!   Suffixes apply to names only, never to `(...)` or calls (Iris's rule; OptiFine's names
//!   simply contain the dots).
//! * Vectors come from `vec2/vec3/vec4(...)` and vector uniforms; arithmetic and the numeric
//!   functions work per component (Iris's vector operators), a scalar operand is broadcast.
//!
//! Things that only make sense across frames are evaluated for a single, first frame:
//! `smooth()` returns its input (OptiFine starts a smoothed value at its target), `random()`
//! draws from splitmix64 seeded with [`RANDOM_SEED`], in evaluation order, so a pack's values
//! are the same on every run. Hostile input is bounded: expression trees deeper than
//! [`MAX_DEPTH`] are refused with an error, never a stack overflow.

use std::collections::BTreeMap;
use std::fmt;

use rand_core::{Rng as _, SeedableRng as _};
use rand_xoshiro::SplitMix64;

use crate::macros::{BIOME_CATEGORIES, PRECIPITATIONS};
use crate::properties::Properties;
use crate::uniform_value::{Kind, Value};

/// Seed of `random()`'s generator: the ASCII bytes of "tidepack". Loaders draw from a
/// time-seeded generator; a fixed seed makes the harness's frames reproducible.
pub const RANDOM_SEED: u64 = 0x7469_6465_7061_636B;

/// Deepest expression tree (and parser recursion) accepted. Real packs nest a few levels; the
/// bound keeps parsing, evaluation and dropping of the tree well inside a thread's stack.
pub const MAX_DEPTH: u32 = 200;

/// The declared type of a definition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeclaredType {
    Float,
    Int,
    Bool,
    Vec2,
    Vec3,
    Vec4,
}

impl DeclaredType {
    fn parse(s: &str) -> Option<DeclaredType> {
        Some(match s {
            "float" => DeclaredType::Float,
            "int" => DeclaredType::Int,
            "bool" => DeclaredType::Bool,
            "vec2" => DeclaredType::Vec2,
            "vec3" => DeclaredType::Vec3,
            "vec4" => DeclaredType::Vec4,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            DeclaredType::Float => "float",
            DeclaredType::Int => "int",
            DeclaredType::Bool => "bool",
            DeclaredType::Vec2 => "vec2",
            DeclaredType::Vec3 => "vec3",
            DeclaredType::Vec4 => "vec4",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Sent to the shaders.
    Uniform,
    /// Only usable by later definitions.
    Variable,
}

/// One `uniform.*` / `variable.*` entry of shaders.properties.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Definition {
    pub role: Role,
    pub ty: DeclaredType,
    pub name: String,
    /// The whole key, `uniform.float.dayMixer`.
    pub key: String,
    pub expression: String,
    /// 1-based line of shaders.properties where the entry starts.
    pub line: usize,
}

/// Something wrong with one entry: the entry is left out of the result.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    pub key: String,
    pub line: usize,
    pub message: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "shaders.properties:{}: {}: {}", self.line, self.key, self.message)
    }
}

/// The evaluated custom uniforms of a pack for one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CustomUniforms {
    /// Uniforms by name; `bool` ones as int 0/1 (the harness has no bool uniforms), `int` ones
    /// truncated toward zero like Java's `(int)` cast.
    pub uniforms: BTreeMap<String, Value>,
    /// Variables by name, converted the same way (for reports; shaders never see them).
    pub variables: BTreeMap<String, Value>,
    /// One entry per definition that failed (it is absent from `uniforms`/`variables`) or per
    /// malformed `uniform.`/`variable.` key.
    pub problems: Vec<Problem>,
}

/// Evaluates every custom uniform and variable of shaders.properties for one frame. `standard` holds the
/// standard uniforms by their OptiFine names (`sunAngle`, `cameraPosition`, `worldTime`, ...);
/// booleans such as `is_hurt` may be given as int 0/1. Never panics.
pub fn evaluate(properties: &Properties, standard: &BTreeMap<String, Value>) -> CustomUniforms {
    let (definitions, mut problems) = definitions(properties);
    let mut out = CustomUniforms::default();
    // Every name's lines, to tell "defined further down" from "unknown".
    let mut lines_of: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for d in &definitions {
        lines_of.entry(d.name.as_str()).or_default().push(d.line);
    }
    let mut defined: BTreeMap<String, Val> = BTreeMap::new();
    let mut failed: BTreeMap<String, usize> = BTreeMap::new();
    let mut rng = SplitMix64::seed_from_u64(RANDOM_SEED);
    for d in &definitions {
        let result = parse(&d.expression).and_then(|expr| {
            let mut cx =
                Context { standard, defined: &defined, failed: &failed, lines_of: &lines_of, current: d, rng: &mut rng };
            cx.eval(&expr)
        });
        let converted = result.map_err(|e| e.describe()).and_then(|v| convert(d, v));
        match converted {
            Ok((val, value)) => {
                failed.remove(&d.name);
                defined.insert(d.name.clone(), val);
                match d.role {
                    Role::Uniform => out.uniforms.insert(d.name.clone(), value),
                    Role::Variable => out.variables.insert(d.name.clone(), value),
                };
            }
            Err(message) => {
                // A failed redefinition hides the earlier value: later uses must not see it.
                defined.remove(&d.name);
                failed.insert(d.name.clone(), d.line);
                problems.push(Problem { key: d.key.clone(), line: d.line, message });
            }
        }
    }
    out.problems = problems;
    out
}

/// The `uniform.*` and `variable.*` entries of shaders.properties in file order, and problems
/// with malformed keys.
pub fn definitions(properties: &Properties) -> (Vec<Definition>, Vec<Problem>) {
    let mut defs: Vec<Definition> = Vec::new();
    let mut problems = Vec::new();
    for entry in properties.entries() {
        let (key, value, line) = (entry.key.clone(), entry.value.clone(), entry.line as usize);
        let (role, rest) = if let Some(rest) = key.strip_prefix("uniform.") {
            (Role::Uniform, rest)
        } else if let Some(rest) = key.strip_prefix("variable.") {
            (Role::Variable, rest)
        } else {
            continue;
        };
        let Some((ty, name)) = rest.split_once('.') else {
            problems.push(Problem {
                key: key.clone(),
                line,
                message: "expected <type>.<name> after the prefix, e.g. uniform.float.fadeIn".into(),
            });
            continue;
        };
        let Some(ty) = DeclaredType::parse(ty) else {
            problems.push(Problem {
                key: key.clone(),
                line,
                message: format!("unknown type '{ty}': custom uniforms are float, int, bool, vec2, vec3 or vec4"),
            });
            continue;
        };
        if !is_identifier(name) {
            problems.push(Problem { key: key.clone(), line, message: format!("'{name}' is not a valid GLSL identifier") });
            continue;
        }
        defs.push(Definition { role, ty, name: name.to_string(), key: key.clone(), expression: value, line });
    }
    (defs, problems)
}

/// A `program.<program>.enabled=<expression>` entry of shaders.properties: the program (which
/// may start with its world folder, `world0/composite2`) runs only where the expression of
/// switch options holds; a disabled program is as if the pack had none.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProgramSwitch {
    pub program: String,
    pub expression: String,
    /// 1-based line of shaders.properties where the entry starts.
    pub line: usize,
}

/// Every `program.<program>.enabled` entry of `properties`, in file order.
pub fn program_switches(properties: &Properties) -> Vec<ProgramSwitch> {
    properties
        .with_prefix("program.")
        .filter_map(|(rest, entry)| {
            let program = rest.strip_suffix(".enabled")?;
            Some(ProgramSwitch { program: program.to_string(), expression: entry.value.clone(), line: entry.line as usize })
        })
        .collect()
}

/// Evaluates a boolean expression of switch options (`(BLOOM || SSAO) && !GODRAYS`) with the
/// language of custom uniforms; `options` gives each switch's state. An unknown name or a
/// result that is not a boolean is an error naming it.
pub fn evaluate_switch_expression(switch: &ProgramSwitch, options: &BTreeMap<String, bool>) -> std::result::Result<bool, String> {
    match evaluate_with_names(&switch.expression, &format!("program.{}.enabled", switch.program), switch.line, options)? {
        Val::Bool(on) => Ok(on),
        other => Err(format!("the expression gives a {}, not a boolean", other.type_name())),
    }
}

/// Evaluates a condition of a properties file's `#if` line, its macros already substituted:
/// `names` are the boolean names it may use (`defined_X`); a number is true when it is not
/// zero, as in OptiFine's macro processor.
pub fn evaluate_condition(expression: &str, names: &BTreeMap<String, bool>) -> std::result::Result<bool, String> {
    match evaluate_with_names(expression, "#if", 0, names)? {
        Val::Bool(on) => Ok(on),
        Val::Num(x) => Ok(x != 0.0),
        other => Err(format!("the condition gives a {}, not a boolean or a number", other.type_name())),
    }
}

/// Evaluates `expression` where only the boolean `names` are defined; `key` and `line` name it
/// in errors.
fn evaluate_with_names(expression: &str, key: &str, line: usize, names: &BTreeMap<String, bool>) -> std::result::Result<Val, String> {
    let current = Definition {
        role: Role::Variable,
        ty: DeclaredType::Bool,
        name: String::new(),
        key: key.to_string(),
        expression: expression.to_string(),
        line,
    };
    let defined: BTreeMap<String, Val> = names.iter().map(|(name, on)| (name.clone(), Val::Bool(*on))).collect();
    let standard = BTreeMap::new();
    let failed = BTreeMap::new();
    let lines_of = BTreeMap::new();
    let mut rng = SplitMix64::seed_from_u64(RANDOM_SEED);
    let value = parse(expression).and_then(|expr| {
        let mut cx = Context { standard: &standard, defined: &defined, failed: &failed, lines_of: &lines_of, current: &current, rng: &mut rng };
        cx.eval(&expr)
    });
    value.map_err(|e| e.describe())
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_') && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

// ---------------------------------------------------------------------------------------------
// Expressions

/// An error in an expression, at a 1-based character position of it (0: the whole expression).
#[derive(Clone, Debug, PartialEq, Eq)]
struct ExprError {
    at: usize,
    message: String,
}

impl ExprError {
    fn new(at: usize, message: impl Into<String>) -> ExprError {
        ExprError { at, message: message.into() }
    }

    fn describe(self) -> String {
        if self.at == 0 { self.message } else { format!("{} (at character {} of the expression)", self.message, self.at) }
    }
}

type Result<T> = std::result::Result<T, ExprError>;

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Number(f64),
    /// A name, with any `.x` / `.0` suffixes it carries.
    Name(String),
    Open,
    Close,
    Comma,
    Op(Op),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Not,
    And,
    Or,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
}

impl Op {
    fn symbol(self) -> &'static str {
        match self {
            Op::Add => "+",
            Op::Sub => "-",
            Op::Mul => "*",
            Op::Div => "/",
            Op::Rem => "%",
            Op::Not => "!",
            Op::And => "&&",
            Op::Or => "||",
            Op::Lt => "<",
            Op::Le => "<=",
            Op::Gt => ">",
            Op::Ge => ">=",
            Op::Eq => "==",
            Op::Ne => "!=",
        }
    }

    /// Binding strength of the binary operator (higher binds tighter), as in C and GLSL.
    fn precedence(self) -> Option<u8> {
        Some(match self {
            Op::Or => 1,
            Op::And => 2,
            Op::Eq | Op::Ne => 3,
            Op::Lt | Op::Le | Op::Gt | Op::Ge => 4,
            Op::Add | Op::Sub => 5,
            Op::Mul | Op::Div | Op::Rem => 6,
            Op::Not => return None,
        })
    }
}

fn describe_token(t: &Token) -> String {
    match t {
        Token::Number(n) => format!("number {n}"),
        Token::Name(n) => format!("'{n}'"),
        Token::Open => "'('".into(),
        Token::Close => "')'".into(),
        Token::Comma => "','".into(),
        Token::Op(op) => format!("'{}'", op.symbol()),
    }
}

/// Tokens with their 1-based character positions.
fn tokenize(text: &str) -> Result<Vec<(Token, usize)>> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let at = i + 1;
        let next = chars.get(i + 1).copied();
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        if c.is_ascii_digit() || (c == '.' && next.is_some_and(|n| n.is_ascii_digit())) {
            let start = i;
            while i < chars.len() && chars[i].is_ascii_digit() {
                i += 1;
            }
            if i < chars.len() && chars[i] == '.' {
                i += 1;
                while i < chars.len() && chars[i].is_ascii_digit() {
                    i += 1;
                }
            }
            // An exponent only when digits follow, so `2e` stays an error below.
            if i < chars.len() && matches!(chars[i], 'e' | 'E') {
                let mut k = i + 1;
                if k < chars.len() && matches!(chars[k], '+' | '-') {
                    k += 1;
                }
                if k < chars.len() && chars[k].is_ascii_digit() {
                    i = k;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let literal: String = chars[start..i].iter().collect();
            if i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_' || chars[i] == '.') {
                return Err(ExprError::new(i + 1, format!("unexpected '{}' after the number {literal}", chars[i])));
            }
            let value = literal.parse::<f64>().map_err(|_| ExprError::new(at, format!("malformed number '{literal}'")))?;
            out.push((Token::Number(value), at));
            continue;
        }
        if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_' || chars[i] == '.') {
                i += 1;
            }
            out.push((Token::Name(chars[start..i].iter().collect()), at));
            continue;
        }
        let two = |a: char, b: char| c == a && next == Some(b);
        let (token, len) = if two('&', '&') {
            (Token::Op(Op::And), 2)
        } else if two('|', '|') {
            (Token::Op(Op::Or), 2)
        } else if two('<', '=') {
            (Token::Op(Op::Le), 2)
        } else if two('>', '=') {
            (Token::Op(Op::Ge), 2)
        } else if two('=', '=') {
            (Token::Op(Op::Eq), 2)
        } else if two('!', '=') {
            (Token::Op(Op::Ne), 2)
        } else {
            let token = match c {
                '+' => Token::Op(Op::Add),
                '-' => Token::Op(Op::Sub),
                '*' => Token::Op(Op::Mul),
                '/' => Token::Op(Op::Div),
                '%' => Token::Op(Op::Rem),
                '!' => Token::Op(Op::Not),
                '<' => Token::Op(Op::Lt),
                '>' => Token::Op(Op::Gt),
                '(' => Token::Open,
                ')' => Token::Close,
                ',' => Token::Comma,
                '=' => return Err(ExprError::new(at, "unexpected '=': comparison is '=='")),
                '&' => return Err(ExprError::new(at, "unexpected '&': logical and is '&&'")),
                '|' => return Err(ExprError::new(at, "unexpected '|': logical or is '||'")),
                other => return Err(ExprError::new(at, format!("unexpected character '{other}'"))),
            };
            (token, 1)
        };
        out.push((token, at));
        i += len;
    }
    Ok(out)
}

#[derive(Clone, Debug, PartialEq)]
enum Expr {
    Number(f64),
    Name { name: String, at: usize },
    Unary { op: Op, at: usize, operand: Box<Expr> },
    Binary { op: Op, at: usize, left: Box<Expr>, right: Box<Expr> },
    Call { name: String, at: usize, args: Vec<Expr> },
}

fn parse(text: &str) -> Result<Expr> {
    let tokens = tokenize(text)?;
    if tokens.is_empty() {
        return Err(ExprError::new(0, "empty expression"));
    }
    let mut parser = Parser { tokens: &tokens, next: 0, end: text.chars().count() + 1 };
    let (expr, _) = parser.binary(0, 0)?;
    if let Some((token, at)) = tokens.get(parser.next) {
        return Err(ExprError::new(*at, format!("unexpected {} after a complete expression", describe_token(token))));
    }
    Ok(expr)
}

/// Precedence climbing; every function returns the tree and its height.
struct Parser<'a> {
    tokens: &'a [(Token, usize)],
    next: usize,
    /// Position reported for "unexpected end".
    end: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&(Token, usize)> {
        self.tokens.get(self.next)
    }

    fn position(&self) -> usize {
        self.peek().map_or(self.end, |t| t.1)
    }

    fn too_deep(at: usize) -> ExprError {
        ExprError::new(at, format!("expression nested deeper than {MAX_DEPTH} levels"))
    }

    fn binary(&mut self, min_precedence: u8, depth: u32) -> Result<(Expr, u32)> {
        let (mut left, mut height) = self.unary(depth)?;
        while let Some((Token::Op(op), at)) = self.peek() {
            let (op, at) = (*op, *at);
            let Some(precedence) = op.precedence() else { break };
            if precedence < min_precedence {
                break;
            }
            self.next += 1;
            let (right, right_height) = self.binary(precedence + 1, depth + 1)?;
            height = height.max(right_height) + 1;
            // A long left-leaning chain (`a+a+a+...`) is built by this loop, not by recursion,
            // so its height is checked here.
            if height > MAX_DEPTH {
                return Err(Self::too_deep(at));
            }
            left = Expr::Binary { op, at, left: Box::new(left), right: Box::new(right) };
        }
        Ok((left, height))
    }

    fn unary(&mut self, depth: u32) -> Result<(Expr, u32)> {
        if depth > MAX_DEPTH {
            return Err(Self::too_deep(self.position()));
        }
        if let Some((Token::Op(op @ (Op::Sub | Op::Not)), at)) = self.peek() {
            let (op, at) = (*op, *at);
            self.next += 1;
            let (operand, height) = self.unary(depth + 1)?;
            return Ok((Expr::Unary { op, at, operand: Box::new(operand) }, height + 1));
        }
        self.primary(depth)
    }

    fn primary(&mut self, depth: u32) -> Result<(Expr, u32)> {
        let Some((token, at)) = self.peek().cloned() else {
            return Err(ExprError::new(self.end, "unexpected end of the expression: a value is missing"));
        };
        self.next += 1;
        match token {
            Token::Number(n) => Ok((Expr::Number(n), 1)),
            Token::Name(name) => {
                if self.peek().map(|t| &t.0) != Some(&Token::Open) {
                    return Ok((Expr::Name { name, at }, 1));
                }
                self.next += 1;
                let mut args = Vec::new();
                let mut height = 0;
                if self.peek().map(|t| &t.0) == Some(&Token::Close) {
                    self.next += 1;
                } else {
                    loop {
                        let (arg, h) = self.binary(0, depth + 1)?;
                        height = height.max(h);
                        args.push(arg);
                        match self.peek() {
                            Some((Token::Comma, _)) => self.next += 1,
                            Some((Token::Close, _)) => {
                                self.next += 1;
                                break;
                            }
                            Some((t, at)) => {
                                return Err(ExprError::new(
                                    *at,
                                    format!("expected ',' or ')' in the arguments of {name}(), found {}", describe_token(t)),
                                ));
                            }
                            None => return Err(ExprError::new(self.end, format!("missing ')' closing {name}("))),
                        }
                    }
                }
                Ok((Expr::Call { name, at, args }, height + 1))
            }
            Token::Open => {
                let (inner, height) = self.binary(0, depth + 1)?;
                match self.peek() {
                    Some((Token::Close, _)) => {
                        self.next += 1;
                        Ok((inner, height))
                    }
                    Some((t, at)) => Err(ExprError::new(*at, format!("expected ')', found {}", describe_token(t)))),
                    None => Err(ExprError::new(self.end, format!("missing ')' for the '(' at character {at}"))),
                }
            }
            other => Err(ExprError::new(at, format!("expected a value, found {}", describe_token(&other)))),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Values and evaluation

#[derive(Clone, Debug, PartialEq)]
enum Val {
    Num(f64),
    Bool(bool),
    /// 2 to 4 components.
    Vector(Vec<f64>),
    /// Column-major; only readable element by element.
    Matrix { columns: u8, rows: u8, data: Vec<f64> },
}

impl Val {
    fn type_name(&self) -> String {
        match self {
            Val::Num(_) => "float".into(),
            Val::Bool(_) => "bool".into(),
            Val::Vector(v) => format!("vec{}", v.len()),
            Val::Matrix { columns, rows, .. } if columns == rows => format!("mat{columns}"),
            Val::Matrix { columns, rows, .. } => format!("mat{columns}x{rows}"),
        }
    }
}

/// Standard parameters OptiFine and Iris treat as booleans; the harness passes them as ints.
const BOOL_PARAMETERS: [&str; 18] = [
    "is_alive",
    "is_burning",
    "is_child",
    "is_glowing",
    "is_hurt",
    "is_in_lava",
    "is_in_water",
    "is_invisible",
    "is_on_ground",
    "is_ridden",
    "is_riding",
    "is_sneaking",
    "is_sprinting",
    "is_wet",
    "firstPersonCamera",
    "isSpectator",
    "hasCeiling",
    "hasSkylight",
];

fn from_standard(name: &str, value: &Value) -> std::result::Result<Val, String> {
    if value.array.is_some() {
        return Err(format!("'{name}' is an array ({}); custom uniforms cannot read arrays", value.glsl_type()));
    }
    let count = value.columns as usize * value.rows as usize;
    if value.data.len() != count || count == 0 {
        return Err(format!("'{name}' has {} components for a {}", value.data.len(), value.glsl_type()));
    }
    Ok(match (value.columns, value.rows) {
        (1, 1) if BOOL_PARAMETERS.contains(&name) => Val::Bool(value.data[0] != 0.0),
        (1, 1) => Val::Num(value.data[0]),
        (1, _) => Val::Vector(value.data.clone()),
        (columns, rows) => Val::Matrix { columns, rows, data: value.data.clone() },
    })
}

/// Index named by a component suffix: xyzw, rgba, stpq or a digit.
fn component_index(suffix: &str) -> Option<usize> {
    Some(match suffix {
        "x" | "r" | "s" | "0" => 0,
        "y" | "g" | "t" | "1" => 1,
        "z" | "b" | "p" | "2" => 2,
        "w" | "a" | "q" | "3" => 3,
        // Larger digits parse so that the error can say the value has no such component.
        digits if !digits.is_empty() && digits.bytes().all(|c| c.is_ascii_digit()) => digits.parse().ok()?,
        _ => return None,
    })
}

struct Context<'a> {
    standard: &'a BTreeMap<String, Value>,
    defined: &'a BTreeMap<String, Val>,
    failed: &'a BTreeMap<String, usize>,
    lines_of: &'a BTreeMap<&'a str, Vec<usize>>,
    current: &'a Definition,
    rng: &'a mut SplitMix64,
}

impl Context<'_> {
    fn eval(&mut self, expr: &Expr) -> Result<Val> {
        match expr {
            Expr::Number(n) => Ok(Val::Num(*n)),
            Expr::Name { name, at } => self.lookup(name, *at),
            Expr::Unary { op, at, operand } => {
                let v = self.eval(operand)?;
                match (op, v) {
                    (Op::Not, Val::Bool(b)) => Ok(Val::Bool(!b)),
                    (Op::Sub, v @ (Val::Num(_) | Val::Vector(_))) => map_numeric(&[v], |x| -x[0]).map_err(|m| ExprError::new(*at, m)),
                    (op, v) => Err(ExprError::new(*at, format!("no operator '{}' for a {}", op.symbol(), v.type_name()))),
                }
            }
            Expr::Binary { op, at, left, right } => {
                // Both operands are always evaluated, so every type error is reported; the only
                // side effect skipped by short-circuiting would be a random() draw.
                let l = self.eval(left)?;
                let r = self.eval(right)?;
                binary(*op, l, r).map_err(|m| ExprError::new(*at, m))
            }
            Expr::Call { name, at, args } => self.call(name, *at, args),
        }
    }

    fn lookup(&self, full: &str, at: usize) -> Result<Val> {
        let mut parts = full.split('.');
        let base = parts.next().unwrap_or_default();
        let mut value = self.base(base, at)?;
        let mut path = base.to_string();
        for suffix in parts {
            let index = component_index(suffix)
                .ok_or_else(|| ExprError::new(at, format!("'{path}' has no component '{suffix}' (use .x/.y/.z/.w, .r/.g/.b/.a, .s/.t/.p/.q or .0-.3)")))?;
            value = match value {
                Val::Vector(v) if index < v.len() => Val::Num(v[index]),
                Val::Matrix { columns, rows, data } if index < columns as usize => {
                    let r = rows as usize;
                    Val::Vector(data[index * r..(index + 1) * r].to_vec())
                }
                v @ (Val::Vector(_) | Val::Matrix { .. }) => {
                    return Err(ExprError::new(at, format!("'{path}' is a {}: it has no component '{suffix}'", v.type_name())));
                }
                v => {
                    return Err(ExprError::new(at, format!("'{path}' is a {}: only vectors and matrices have components", v.type_name())));
                }
            };
            path = format!("{path}.{suffix}");
        }
        Ok(value)
    }

    fn base(&self, name: &str, at: usize) -> Result<Val> {
        match name {
            "pi" => return Ok(Val::Num(std::f64::consts::PI)),
            "true" => return Ok(Val::Bool(true)),
            "false" => return Ok(Val::Bool(false)),
            _ => {}
        }
        if let Some(v) = self.defined.get(name) {
            return Ok(v.clone());
        }
        if let Some(line) = self.failed.get(name) {
            return Err(ExprError::new(at, format!("'{name}' has no value: its definition at line {line} failed")));
        }
        if let Some(v) = self.standard.get(name) {
            return from_standard(name, v).map_err(|m| ExprError::new(at, m));
        }
        if let Some(i) = BIOME_CATEGORIES.iter().position(|c| *c == name) {
            return Ok(Val::Num(i as f64));
        }
        if let Some(i) = PRECIPITATIONS.iter().position(|c| *c == name) {
            return Ok(Val::Num(i as f64));
        }
        if name == self.current.name {
            return Err(ExprError::new(at, format!("'{name}' is used in its own definition")));
        }
        if let Some(line) = self.lines_of.get(name).and_then(|lines| lines.iter().find(|l| **l > self.current.line)) {
            return Err(ExprError::new(
                at,
                format!("'{name}' is used before its definition at line {line} (definitions are evaluated in file order)"),
            ));
        }
        if name.starts_with("BIOME_") {
            return Err(ExprError::new(at, format!("unknown biome constant '{name}' (biome ids depend on the game version; none given)")));
        }
        Err(ExprError::new(at, format!("unknown variable '{name}'")))
    }

    fn call(&mut self, name: &str, at: usize, args: &[Expr]) -> Result<Val> {
        let err = |m: String| ExprError::new(at, m);
        let arity = |n: usize| -> Result<()> {
            if args.len() == n {
                Ok(())
            } else {
                Err(ExprError::new(at, format!("{name}() takes {n} argument{}, found {}", if n == 1 { "" } else { "s" }, args.len())))
            }
        };
        if name == "smooth" {
            return self.smooth(at, args);
        }
        let values = self.eval_all(args)?;
        let numbers = |fname: &str| -> Result<Vec<f64>> {
            values
                .iter()
                .enumerate()
                .map(|(i, v)| match v {
                    Val::Num(x) => Ok(*x),
                    v => Err(ExprError::new(at, format!("argument {} of {fname}() must be a float, found {}", i + 1, v.type_name()))),
                })
                .collect()
        };
        let per_component = |n: usize, f: fn(&[f64]) -> f64| -> Result<Val> {
            arity(n)?;
            map_numeric(&values, f).map_err(|m| ExprError::new(at, format!("{name}(): {m}")))
        };
        if let Some((count, f)) = numeric_function(name, args.len()) {
            return per_component(count, f);
        }
        match name {
            "min" | "max" => {
                if args.len() < 2 {
                    return Err(err(format!("{name}() takes at least 2 arguments, found {}", args.len())));
                }
                let pick: fn(f64, f64) -> f64 = if name == "min" { f64::min } else { f64::max };
                let mut acc = values[0].clone();
                for v in &values[1..] {
                    acc = map_numeric(&[acc, v.clone()], |x| pick(x[0], x[1])).map_err(|m| err(format!("{name}(): {m}")))?;
                }
                // A lone bool argument would slip through the fold of one value.
                map_numeric(&[acc], |x| x[0]).map_err(|m| err(format!("{name}(): {m}")))
            }
            "between" => {
                arity(3)?;
                let x = numbers(name)?;
                Ok(Val::Bool(x[0] >= x[1] && x[0] <= x[2]))
            }
            "equals" => {
                arity(3)?;
                let x = numbers(name)?;
                Ok(Val::Bool((x[0] - x[1]).abs() <= x[2]))
            }
            "in" => {
                if args.len() < 2 {
                    return Err(err(format!("in() takes a value and at least one candidate, found {} argument(s)", args.len())));
                }
                let x = numbers(name)?;
                Ok(Val::Bool(x[1..].contains(&x[0])))
            }
            "if" | "ifb" => select(name, &values).map_err(err),
            "print" => {
                arity(3)?;
                numbers(name)?;
                Ok(values[2].clone())
            }
            "random" => match args.len() {
                0 => Ok(Val::Num(self.unit_random())),
                2 => {
                    let x = numbers(name)?;
                    Ok(Val::Num(x[0] + self.unit_random() * (x[1] - x[0])))
                }
                n => Err(err(format!("random() takes 0 or 2 arguments, found {n}"))),
            },
            "randomInt" => {
                let x = numbers(name)?;
                let (low, high) = match x.len() {
                    0 => (i32::MIN as f64, i32::MAX as f64 + 1.0),
                    1 => (0.0, x[0].trunc()),
                    2 => (x[0].trunc(), x[1].trunc()),
                    n => return Err(err(format!("randomInt() takes 0 to 2 arguments, found {n}"))),
                };
                if high <= low {
                    return Err(err(format!("randomInt(): empty range [{low}, {high})")));
                }
                Ok(Val::Num((low + (self.unit_random() * (high - low)).floor()).min(high - 1.0)))
            }
            "vec2" => construct(2, &values).map_err(err),
            "vec3" => construct(3, &values).map_err(err),
            "vec4" => construct(4, &values).map_err(err),
            _ => Err(err(format!("unknown function '{name}()'"))),
        }
    }

    /// `smooth()`, for one frame: its value starts at its target. Whether its first argument is
    /// a literal id decides which argument the target is, so it is looked at before evaluation.
    fn smooth(&mut self, at: usize, args: &[Expr]) -> Result<Val> {
        let err = |m: String| ExprError::new(at, m);
        let target = match args.len() {
            1 => 0,
            // (id, value) or (id, value, fade) when the first argument is a constant id;
            // otherwise (value, fade) / (value, fadeIn, fadeOut).
            2 | 3 if matches!(args[0], Expr::Number(_)) => 1,
            2 | 3 => 0,
            4 => 1,
            n => return Err(err(format!("smooth() takes 1 to 4 arguments, found {n}"))),
        };
        let values = self.eval_all(args)?;
        for (i, v) in values.iter().enumerate() {
            if !matches!(v, Val::Num(_)) {
                return Err(err(format!("argument {} of smooth() must be a float, found {}", i + 1, v.type_name())));
            }
        }
        // One frame: the smoothed value starts at its target.
        Ok(values[target].clone())
    }

    fn eval_all(&mut self, args: &[Expr]) -> Result<Vec<Val>> {
        args.iter().map(|a| self.eval(a)).collect()
    }

    /// Uniform in [0, 1) from the top 53 bits.
    fn unit_random(&mut self) -> f64 {
        (self.rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Java's Math.signum: zero (of either sign) and NaN come back unchanged.
fn signum(x: f64) -> f64 {
    if x == 0.0 || x.is_nan() { x } else { x.signum() }
}

/// Applies `f` per component: numbers and same-size vectors, numbers broadcast to the size.
fn map_numeric(args: &[Val], f: impl Fn(&[f64]) -> f64) -> std::result::Result<Val, String> {
    let mut size = None;
    for (i, a) in args.iter().enumerate() {
        match a {
            Val::Num(_) => {}
            Val::Vector(v) => match size {
                Some(n) if n != v.len() => {
                    let names: Vec<String> = args.iter().map(Val::type_name).collect();
                    return Err(format!("mismatched vector sizes ({})", names.join(", ")));
                }
                _ => size = Some(v.len()),
            },
            other => {
                let place = if args.len() == 1 { String::new() } else { format!(" {}", i + 1) };
                return Err(format!("operand{place} is a {}, not a number or vector", other.type_name()));
            }
        }
    }
    let component = |a: &Val, k: usize| match a {
        Val::Num(x) => *x,
        Val::Vector(v) => v[k],
        _ => f64::NAN,
    };
    let mut scratch = [0.0; 4];
    let mut at = |k: usize| {
        for (slot, a) in scratch.iter_mut().zip(args) {
            *slot = component(a, k);
        }
        f(&scratch[..args.len().min(4)])
    };
    Ok(match size {
        None => Val::Num(at(0)),
        Some(n) => Val::Vector((0..n).map(at).collect()),
    })
}

fn binary(op: Op, l: Val, r: Val) -> std::result::Result<Val, String> {
    let mismatch = |l: &Val, r: &Val| format!("no operator '{}' for {} and {}", op.symbol(), l.type_name(), r.type_name());
    match op {
        Op::Add | Op::Sub | Op::Mul | Op::Div | Op::Rem => {
            let f: fn(&[f64]) -> f64 = match op {
                Op::Add => |x| x[0] + x[1],
                Op::Sub => |x| x[0] - x[1],
                Op::Mul => |x| x[0] * x[1],
                Op::Div => |x| x[0] / x[1],
                _ => |x| x[0] % x[1],
            };
            if !matches!(l, Val::Num(_) | Val::Vector(_)) || !matches!(r, Val::Num(_) | Val::Vector(_)) {
                return Err(mismatch(&l, &r));
            }
            map_numeric(&[l.clone(), r.clone()], f).map_err(|_| mismatch(&l, &r))
        }
        Op::Lt | Op::Le | Op::Gt | Op::Ge => match (&l, &r) {
            (Val::Num(a), Val::Num(b)) => Ok(Val::Bool(match op {
                Op::Lt => a < b,
                Op::Le => a <= b,
                Op::Gt => a > b,
                _ => a >= b,
            })),
            _ => Err(mismatch(&l, &r)),
        },
        Op::Eq | Op::Ne => {
            let same = match (&l, &r) {
                (Val::Num(a), Val::Num(b)) => a == b,
                (Val::Bool(a), Val::Bool(b)) => a == b,
                (Val::Vector(a), Val::Vector(b)) if a.len() == b.len() => a == b,
                _ => return Err(mismatch(&l, &r)),
            };
            Ok(Val::Bool(same == (op == Op::Eq)))
        }
        Op::And | Op::Or => match (&l, &r) {
            (Val::Bool(a), Val::Bool(b)) => Ok(Val::Bool(if op == Op::And { *a && *b } else { *a || *b })),
            _ => Err(mismatch(&l, &r)),
        },
        Op::Not => Err(mismatch(&l, &r)),
    }
}

/// `if(c1, v1, c2, v2, ..., else)`: the value of the first true condition. `ifb` is OptiFine's
/// spelling for boolean values; `if` here accepts any type as long as the branches agree.
fn select(name: &str, values: &[Val]) -> std::result::Result<Val, String> {
    if values.len() < 3 || values.len().is_multiple_of(2) {
        return Err(format!("{name}() takes (condition, value, ..., else value): an odd number of at least 3 arguments, found {}", values.len()));
    }
    let branches: Vec<usize> = (1..values.len()).step_by(2).chain([values.len() - 1]).collect();
    let ty = values[1].type_name();
    for &i in &branches {
        if name == "ifb" && !matches!(values[i], Val::Bool(_)) {
            return Err(format!("ifb() selects bools; argument {} is a {}", i + 1, values[i].type_name()));
        }
        if values[i].type_name() != ty {
            return Err(format!("the values of {name}() differ in type: {ty} and {}", values[i].type_name()));
        }
    }
    // Every condition is checked before one is picked, so a bad one is reported wherever it is.
    let mut chosen = None;
    for (k, pair) in values[..values.len() - 1].chunks(2).enumerate() {
        match pair[0] {
            Val::Bool(true) => chosen = chosen.or(Some(&pair[1])),
            Val::Bool(false) => {}
            ref other => return Err(format!("argument {} of {name}() must be a bool condition, found {}", 2 * k + 1, other.type_name())),
        }
    }
    Ok(chosen.unwrap_or(&values[values.len() - 1]).clone())
}

/// `vecN(...)`: one number fills every component; otherwise numbers and vectors are laid end
/// to end and must make exactly N components (GLSL's constructors).
fn construct(n: usize, values: &[Val]) -> std::result::Result<Val, String> {
    if let [Val::Num(x)] = values {
        return Ok(Val::Vector(vec![*x; n]));
    }
    let mut out = Vec::with_capacity(n);
    for (i, v) in values.iter().enumerate() {
        match v {
            Val::Num(x) => out.push(*x),
            Val::Vector(c) => out.extend_from_slice(c),
            other => return Err(format!("argument {} of vec{n}() must be a float or vector, found {}", i + 1, other.type_name())),
        }
    }
    if out.len() != n {
        return Err(format!("vec{n}() needs {n} components, found {}", out.len()));
    }
    Ok(Val::Vector(out))
}

/// Checks a result against its declaration: the value later definitions see and the uniform.
fn convert(d: &Definition, v: Val) -> std::result::Result<(Val, Value), String> {
    let vector = |data: Vec<f64>| Value { kind: Kind::Float, columns: 1, rows: data.len() as u8, array: None, data };
    match (d.ty, v) {
        (DeclaredType::Float, Val::Num(x)) => Ok((Val::Num(x), Value::float(x))),
        (DeclaredType::Int, Val::Num(x)) => {
            // Java's (int) cast: toward zero, saturating, NaN to 0.
            let i = if x.is_nan() { 0 } else { x.trunc().clamp(i32::MIN as f64, i32::MAX as f64) as i64 };
            Ok((Val::Num(i as f64), Value::int(i)))
        }
        (DeclaredType::Bool, Val::Bool(b)) => Ok((Val::Bool(b), Value::int(b as i64))),
        (DeclaredType::Vec2, Val::Vector(c)) if c.len() == 2 => Ok((Val::Vector(c.clone()), vector(c))),
        (DeclaredType::Vec3, Val::Vector(c)) if c.len() == 3 => Ok((Val::Vector(c.clone()), vector(c))),
        (DeclaredType::Vec4, Val::Vector(c)) if c.len() == 4 => Ok((Val::Vector(c.clone()), vector(c))),
        (ty, v) => Err(format!(
            "the expression is a {}, but the {} is declared {}",
            v.type_name(),
            if d.role == Role::Uniform { "uniform" } else { "variable" },
            ty.name()
        )),
    }
}

/// The functions that apply per component to numbers: argument count and function, by name
/// (`args`: how many the call has, for the names that take one or two).
fn numeric_function(name: &str, args: usize) -> Option<(usize, fn(&[f64]) -> f64)> {
    let function: (usize, fn(&[f64]) -> f64) = match name {
        "sin" => (1, |x| x[0].sin()),
        "cos" => (1, |x| x[0].cos()),
        "tan" => (1, |x| x[0].tan()),
        "asin" => (1, |x| x[0].asin()),
        "acos" => (1, |x| x[0].acos()),
        "atan" if args == 2 => (2, |x| x[0].atan2(x[1])),
        "atan" => (1, |x| x[0].atan()),
        "atan2" => (2, |x| x[0].atan2(x[1])),
        "torad" | "radians" => (1, |x| x[0].to_radians()),
        "todeg" | "degrees" => (1, |x| x[0].to_degrees()),
        "abs" => (1, |x| x[0].abs()),
        "floor" => (1, |x| x[0].floor()),
        "ceil" => (1, |x| x[0].ceil()),
        "exp" => (1, |x| x[0].exp()),
        "exp2" => (1, |x| x[0].exp2()),
        "exp10" => (1, |x| 10f64.powf(x[0])),
        "frac" => (1, |x| x[0] - x[0].floor()),
        "log" if args == 2 => (2, |x| x[1].ln() / x[0].ln()),
        "log" => (1, |x| x[0].ln()),
        "log2" => (1, |x| x[0].log2()),
        "log10" => (1, |x| x[0].log10()),
        "pow" => (2, |x| x[0].powf(x[1])),
        // Java's Math.round: halves go up.
        "round" => (1, |x| (x[0] + 0.5).floor()),
        "signum" | "sign" => (1, |x| signum(x[0])),
        "sqrt" => (1, |x| x[0].sqrt()),
        "fmod" => (2, |x| ((x[0] % x[1]) + x[1]) % x[1]),
        "clamp" => (3, |x| x[0].min(x[2]).max(x[1])),
        "lerp" => (3, |x| x[1] + (x[2] - x[1]) * x[0]),
        "mix" => (3, |x| x[0] + (x[1] - x[0]) * x[2]),
        // Iris's name for GLSL's step(edge, x).
        "edge" => (2, |x| if x[1] < x[0] { 0.0 } else { 1.0 }),
        _ => return None,
    };
    Some(function)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn program_switches_evaluate_switch_options() {
        let properties = "program.world0/composite4.enabled=DOF || TAA\nprogram.deferred.enabled = (BLOOM && !SSAO)\nuniform.float.x = 1\n";
        let switches = program_switches(&Properties::parse_plain(properties));
        assert_eq!(switches.iter().map(|s| (s.program.as_str(), s.line)).collect::<Vec<_>>(), [("world0/composite4", 1), ("deferred", 2)]);
        let options: BTreeMap<String, bool> =
            [("DOF", false), ("TAA", true), ("BLOOM", true), ("SSAO", true)].into_iter().map(|(n, v)| (n.to_string(), v)).collect();
        assert_eq!(evaluate_switch_expression(&switches[0], &options), Ok(true));
        assert_eq!(evaluate_switch_expression(&switches[1], &options), Ok(false));
        let unknown = ProgramSwitch { program: "composite".into(), expression: "GODRAYS".into(), line: 3 };
        assert!(evaluate_switch_expression(&unknown, &options).unwrap_err().contains("GODRAYS"));
        let number = ProgramSwitch { program: "composite".into(), expression: "1 + 2".into(), line: 4 };
        assert!(evaluate_switch_expression(&number, &options).unwrap_err().contains("not a boolean"));
    }
    use glam::{DMat4, DVec3, DVec4};

    fn standard() -> BTreeMap<String, Value> {
        let mut s = BTreeMap::new();
        s.insert("sunAngle".to_string(), Value::float(0.125));
        s.insert("viewWidth".to_string(), Value::float(1920.0));
        s.insert("viewHeight".to_string(), Value::float(1080.0));
        s.insert("frameTimeCounter".to_string(), Value::float(2.0));
        s.insert("worldTime".to_string(), Value::int(6000));
        s.insert("cameraPosition".to_string(), Value::vec3(DVec3::new(1.0, 2.0, 3.0)));
        s.insert("skyColor".to_string(), Value::vec3(DVec3::new(0.25, 0.5, 0.75)));
        s.insert("eyeBrightness".to_string(), Value::ivec2(0, 240));
        s.insert("fogColor4".to_string(), Value::vec4(DVec4::new(1.0, 2.0, 3.0, 4.0)));
        s.insert("is_hurt".to_string(), Value::int(1));
        s.insert("is_sneaking".to_string(), Value::int(0));
        // Column c, row r holds 10c + r.
        let m = DMat4::from_cols_array(&std::array::from_fn(|i| ((i / 4) * 10 + i % 4) as f64));
        s.insert("gbufferModelView".to_string(), Value::mat4(m));
        s.insert("tp_TextureMatrix".to_string(), Value::mat4_array(&[DMat4::IDENTITY]));
        s
    }

    fn run(properties: &str) -> CustomUniforms {
        evaluate(&Properties::parse_plain(properties), &standard())
    }

    fn uniform(properties: &str, name: &str) -> Value {
        let out = run(properties);
        assert!(out.problems.is_empty(), "{:?}", out.problems);
        out.uniforms.get(name).cloned().unwrap_or_else(|| panic!("no uniform {name}: {out:?}"))
    }

    fn f(expr: &str) -> f64 {
        let v = uniform(&format!("uniform.float.v = {expr}"), "v");
        assert_eq!(v.glsl_type(), "float");
        v.data[0]
    }

    fn b(expr: &str) -> bool {
        let v = uniform(&format!("uniform.bool.v = {expr}"), "v");
        assert_eq!(v.glsl_type(), "int");
        assert!(v.data[0] == 0.0 || v.data[0] == 1.0);
        v.data[0] == 1.0
    }

    fn vector(expr: &str, n: usize) -> Vec<f64> {
        let v = uniform(&format!("uniform.vec{n}.v = {expr}"), "v");
        assert_eq!(v.glsl_type(), format!("vec{n}"));
        v.data
    }

    /// The one problem of a float uniform `v` defined on line 1.
    fn error(expr: &str) -> String {
        let out = run(&format!("uniform.float.v = {expr}"));
        assert!(out.uniforms.is_empty(), "{out:?}");
        assert_eq!(out.problems.len(), 1, "{:?}", out.problems);
        assert_eq!(out.problems[0].line, 1);
        assert_eq!(out.problems[0].key, "uniform.float.v");
        out.problems[0].message.clone()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn examples_of_the_brief_evaluate_in_file_order() {
        let out = run("uniform.float.dayMixer = clamp(sunAngle * 4.0, 0.0, 1.0)\n\
                       variable.float.t = frameTimeCounter * 0.5\n\
                       uniform.vec3.sunDir = vec3(sin(t), cos(t), 0.0)\n\
                       uniform.vec2.pixelSize = vec2(1.0 / viewWidth, 1.0 / viewHeight)\n");
        assert!(out.problems.is_empty(), "{:?}", out.problems);
        assert_eq!(out.uniforms["dayMixer"], Value::float(0.5));
        assert_eq!(out.variables["t"], Value::float(1.0));
        assert!(!out.uniforms.contains_key("t"));
        assert_eq!(out.uniforms["sunDir"], Value::vec3(DVec3::new(1f64.sin(), 1f64.cos(), 0.0)));
        let pixel = &out.uniforms["pixelSize"];
        assert_eq!((pixel.kind, pixel.columns, pixel.rows), (Kind::Float, 1, 2));
        assert_eq!(pixel.data, vec![1.0 / 1920.0, 1.0 / 1080.0]);
    }

    #[test]
    fn properties_syntax_comments_continuations_separators_and_lines() {
        let text = "# comment uniform.float.no = 1\n\
                    ! also a comment\n\
                    \n\
                    screen = A B\n\
                    uniform.float.a = 1.0 + \\\n\
                    \x20   2.0 \\\n\
                    \x20   * 3.0\n\
                    uniform.float.b:a*2\n\
                    uniform.float.c 4\n\
                    \x20\x20variable.float.d=a\\\\\n\
                    uniform.float.e = 5 \\\\\\\n\
                    + 1\n";
        let (defs, problems) = definitions(&Properties::parse_plain(text));
        assert!(problems.is_empty(), "{problems:?}");
        let summary: Vec<(&str, &str, usize)> = defs.iter().map(|d| (d.name.as_str(), d.expression.as_str(), d.line)).collect();
        assert_eq!(
            summary,
            [("a", "1.0 + 2.0 * 3.0", 5), ("b", "a*2", 8), ("c", "4", 9), ("d", "a\\", 10), ("e", "5 \\+ 1", 11)]
        );
        let out = run(text);
        assert_eq!(out.uniforms["a"], Value::float(7.0));
        assert_eq!(out.uniforms["b"], Value::float(14.0));
        assert_eq!(out.uniforms["c"], Value::float(4.0));
        // `a\` and `5 \+ 1` are not expressions: reported with their own lines.
        let lines: Vec<usize> = out.problems.iter().map(|p| p.line).collect();
        assert_eq!(lines, [10, 11]);
        assert!(out.problems[0].message.contains("unexpected character '\\'"), "{:?}", out.problems);
    }

    #[test]
    fn malformed_keys_and_redefinitions() {
        let out = run("uniform.float = 1\nuniform.mat4.m = 1\nvariable.float.2x = 1\nuniform.float.k = 1\nuniform.float.k = 2\n");
        let got: Vec<(usize, &str)> = out.problems.iter().map(|p| (p.line, p.key.as_str())).collect();
        assert_eq!(got, [(1, "uniform.float"), (2, "uniform.mat4.m"), (3, "variable.float.2x")]);
        assert!(out.problems[1].message.contains("unknown type 'mat4'"));
        // The later text wins.
        assert_eq!(out.uniforms["k"], Value::float(2.0));
    }

    #[test]
    fn arithmetic_and_comparison_operators() {
        assert_eq!(f("1 + 2"), 3.0);
        assert_eq!(f("1 - 2"), -1.0);
        assert_eq!(f("3 * 4"), 12.0);
        assert_eq!(f("3 / 4"), 0.75);
        assert_eq!(f("7 % 3"), 1.0);
        // Java's remainder keeps the dividend's sign; fmod is floored.
        assert_eq!(f("-7 % 3"), -1.0);
        assert_eq!(f("-5"), -5.0);
        assert_eq!(f("--5"), 5.0);
        assert_eq!(f("1 / 0"), f64::INFINITY);
        assert!(b("1 < 2") && !b("2 < 2") && b("2 <= 2") && !b("3 <= 2"));
        assert!(b("3 > 2") && !b("2 > 2") && b("2 >= 2") && !b("1 >= 2"));
        assert!(b("2 == 2") && !b("2 == 3") && b("2 != 3") && !b("2 != 2"));
        assert!(b("true == true") && b("true != false"));
        assert!(b("vec2(1, 2) == vec2(1, 2)") && b("vec2(1, 2) != vec2(1, 3)"));
        assert!(b("true && true") && !b("true && false") && b("false || true") && !b("false || false"));
        assert!(b("!false") && !b("!true") && b("!!true"));
        assert!(b("true") && !b("false"));
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(f("1 + 2 * 3"), 7.0);
        assert_eq!(f("(1 + 2) * 3"), 9.0);
        assert_eq!(f("2 - 3 - 4"), -5.0);
        assert_eq!(f("8 / 4 / 2"), 1.0);
        assert_eq!(f("2 * 3 % 4"), 2.0);
        assert_eq!(f("-2 * 3 + 1"), -5.0);
        assert_eq!(f("-(2 + 3)"), -5.0);
        assert_eq!(f("10 - -2"), 12.0);
        assert!(b("1 + 1 == 2"));
        assert!(b("1 < 2 == 3 < 4"));
        assert!(b("true || false && false"));
        assert!(!b("(true || false) && false"));
        assert!(!b("!true || false"));
        assert!(b("1 < 2 && 3 > 2 || false"));
        assert_eq!(f("((((1))))"), 1.0);
    }

    #[test]
    fn numbers_constants_and_parameters() {
        assert_eq!(f(".5 + 1. + 2e1 + 1.5E-1"), 0.5 + 1.0 + 20.0 + 0.15);
        assert_eq!(f("pi"), std::f64::consts::PI);
        assert_eq!(f("worldTime / 1000"), 6.0);
        assert_eq!(f("CAT_NETHER + PPT_SNOW + CAT_NONE"), 18.0);
        assert!(b("is_hurt && !is_sneaking"));
    }

    #[test]
    fn every_function() {
        let x = 0.3f64;
        assert!(close(f("sin(0.3)"), x.sin()));
        assert!(close(f("cos(0.3)"), x.cos()));
        assert!(close(f("tan(0.3)"), x.tan()));
        assert!(close(f("asin(0.3)"), x.asin()));
        assert!(close(f("acos(0.3)"), x.acos()));
        assert!(close(f("atan(0.3)"), x.atan()));
        assert!(close(f("atan2(1, -1)"), 1f64.atan2(-1.0)));
        assert!(close(f("atan(1, -1)"), 1f64.atan2(-1.0)));
        assert!(close(f("torad(180)"), std::f64::consts::PI));
        assert!(close(f("radians(90)"), std::f64::consts::FRAC_PI_2));
        assert!(close(f("todeg(pi)"), 180.0));
        assert!(close(f("degrees(pi / 2)"), 90.0));
        assert_eq!(f("min(3, 1, 2)"), 1.0);
        assert_eq!(f("max(3, 1, 5, 2)"), 5.0);
        assert_eq!(f("min(2, 1)"), 1.0);
        assert_eq!(f("clamp(5, 0, 1)"), 1.0);
        assert_eq!(f("clamp(-5, 0, 1)"), 0.0);
        assert_eq!(f("clamp(0.5, 0, 1)"), 0.5);
        assert_eq!(f("abs(-2.5)"), 2.5);
        assert_eq!(f("floor(-1.5)"), -2.0);
        assert_eq!(f("ceil(-1.5)"), -1.0);
        assert!(close(f("exp(1)"), std::f64::consts::E));
        assert_eq!(f("exp2(3)"), 8.0);
        assert!(close(f("exp10(2)"), 100.0));
        assert!(close(f("frac(-1.25)"), 0.75));
        assert!(close(f("log(exp(2))"), 2.0));
        assert!(close(f("log(2, 8)"), 3.0));
        assert_eq!(f("log2(8)"), 3.0);
        assert!(close(f("log10(1000)"), 3.0));
        assert_eq!(f("pow(2, 10)"), 1024.0);
        assert_eq!(f("round(2.5)"), 3.0);
        assert_eq!(f("round(-2.5)"), -2.0);
        assert_eq!(f("round(1.4)"), 1.0);
        assert_eq!(f("signum(-3)"), -1.0);
        assert_eq!(f("signum(3)"), 1.0);
        assert_eq!(f("signum(0)"), 0.0);
        assert_eq!(f("sign(-0.5)"), -1.0);
        assert_eq!(f("sqrt(16)"), 4.0);
        assert_eq!(f("fmod(-7, 3)"), 2.0);
        assert_eq!(f("fmod(7, 3)"), 1.0);
        assert_eq!(f("lerp(0.25, 2, 6)"), 3.0);
        assert_eq!(f("mix(2, 6, 0.25)"), 3.0);
        assert_eq!(f("edge(0.5, 0.4) + 10 * edge(0.5, 0.6)"), 10.0);
        assert_eq!(f("if(true, 1, 2)"), 1.0);
        assert_eq!(f("if(false, 1, 2)"), 2.0);
        assert_eq!(f("if(false, 1, true, 2, 3)"), 2.0);
        assert_eq!(f("if(false, 1, false, 2, 3)"), 3.0);
        assert_eq!(f("if(true, 1, true, 2, 3)"), 1.0);
        assert_eq!(vector("if(worldTime > 100, vec2(1, 2), vec2(3, 4))", 2), [1.0, 2.0]);
        assert!(b("ifb(false, false, true)"));
        assert!(!b("ifb(is_hurt, false, true)"));
        assert!(b("between(1, 0, 1)") && b("between(0, 0, 1)") && !b("between(1.1, 0, 1)"));
        assert!(b("equals(1.0, 1.05, 0.1)") && !b("equals(1.0, 1.2, 0.1)"));
        assert!(b("in(3, 1, 2, 3)") && !b("in(4, 1, 2, 3)") && b("in(2, 2)"));
        assert_eq!(f("print(1, 10, 42)"), 42.0);
        // smooth: one frame, the smoothed value is its input, whichever form is used.
        assert_eq!(f("smooth(0.7)"), 0.7);
        assert_eq!(f("smooth(1, 0.7)"), 0.7);
        assert_eq!(f("smooth(sunAngle, 5)"), 0.125);
        assert_eq!(f("smooth(2, sunAngle, 5)"), 0.125);
        assert_eq!(f("smooth(sunAngle, 0, 10)"), 0.125);
        assert_eq!(f("smooth(3, sunAngle, 0.5, 0.5)"), 0.125);
        let r = f("random()");
        assert!((0.0..1.0).contains(&r));
        let r = f("random(10, 20)");
        assert!((10.0..20.0).contains(&r));
        let r = f("randomInt(3, 6)");
        assert!(r.fract() == 0.0 && (3.0..6.0).contains(&r));
        let r = f("randomInt(4)");
        assert!(r.fract() == 0.0 && (0.0..4.0).contains(&r));
        assert_eq!(vector("vec2(1, 2)", 2), [1.0, 2.0]);
        assert_eq!(vector("vec3(1, 2, 3)", 3), [1.0, 2.0, 3.0]);
        assert_eq!(vector("vec4(1, 2, 3, 4)", 4), [1.0, 2.0, 3.0, 4.0]);
    }

    #[test]
    fn random_is_seeded_and_advances() {
        let text = "uniform.float.a = random()\nuniform.float.b = random()\n";
        let first = run(text);
        assert_eq!(first, run(text));
        assert_ne!(first.uniforms["a"], first.uniforms["b"]);
        let mut rng = SplitMix64::seed_from_u64(RANDOM_SEED);
        let expected = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        assert_eq!(first.uniforms["a"], Value::float(expected));
    }

    #[test]
    fn vectors_construction_components_and_arithmetic() {
        assert_eq!(f("cameraPosition.x + 10 * cameraPosition.y + 100 * cameraPosition.z"), 321.0);
        assert_eq!(f("skyColor.r + skyColor.g + skyColor.b"), 1.5);
        assert_eq!(f("fogColor4.w + fogColor4.a + fogColor4.q + fogColor4.3"), 16.0);
        assert_eq!(f("cameraPosition.s + cameraPosition.t * 10 + cameraPosition.p * 100"), 321.0);
        assert_eq!(f("eyeBrightness.y"), 240.0);
        assert_eq!(f("gbufferModelView.3.1"), 31.0);
        assert_eq!(f("gbufferModelView.0.2"), 2.0);
        assert_eq!(vector("gbufferModelView.2", 4), [20.0, 21.0, 22.0, 23.0]);
        assert_eq!(vector("cameraPosition", 3), [1.0, 2.0, 3.0]);
        assert_eq!(vector("vec3(0.5)", 3), [0.5; 3]);
        assert_eq!(vector("vec3(vec2(1, 2), 3)", 3), [1.0, 2.0, 3.0]);
        assert_eq!(vector("cameraPosition + vec3(1, 1, 1)", 3), [2.0, 3.0, 4.0]);
        assert_eq!(vector("cameraPosition * 2 - 1", 3), [1.0, 3.0, 5.0]);
        assert_eq!(vector("-cameraPosition / cameraPosition", 3), [-1.0; 3]);
        assert_eq!(vector("abs(vec2(-1, 2))", 2), [1.0, 2.0]);
        assert_eq!(vector("clamp(vec2(-1, 2), 0, 1)", 2), [0.0, 1.0]);
        assert_eq!(vector("max(vec2(0, 5), vec2(1, 2))", 2), [1.0, 5.0]);
        // A vector variable is read like a uniform, components included.
        let out = run("variable.vec3.p = cameraPosition * 2\nuniform.float.py = p.y\nuniform.vec3.q = p\n");
        assert!(out.problems.is_empty(), "{:?}", out.problems);
        assert_eq!(out.uniforms["py"], Value::float(4.0));
        assert_eq!(out.uniforms["q"], Value::vec3(DVec3::new(2.0, 4.0, 6.0)));
        assert_eq!(out.variables["p"], Value::vec3(DVec3::new(2.0, 4.0, 6.0)));
    }

    #[test]
    fn int_and_bool_uniforms() {
        let out = run("uniform.int.day = worldTime / 7000 + 2.9\nuniform.int.neg = -2.9\nuniform.bool.hurt = is_hurt\nuniform.bool.no = 1 > 2\n");
        assert!(out.problems.is_empty(), "{:?}", out.problems);
        assert_eq!(out.uniforms["day"], Value::int(3));
        assert_eq!(out.uniforms["neg"], Value::int(-2));
        assert_eq!(out.uniforms["hurt"], Value::int(1));
        assert_eq!(out.uniforms["no"], Value::int(0));
        // A bool variable used later is a bool again.
        assert_eq!(uniform("variable.bool.x = 1 < 2\nuniform.float.y = if(x, 4, 5)\n", "y"), Value::float(4.0));
        // An int variable holds its truncated value.
        assert_eq!(uniform("variable.int.i = 2.7\nuniform.float.y = i * 2\n", "y"), Value::float(4.0));
    }

    #[test]
    fn declaration_order_and_failed_dependencies() {
        let out = run("uniform.float.a = b + 1\n\
                       variable.float.b = 2\n\
                       uniform.float.c = b + 1\n\
                       variable.float.d = nope\n\
                       uniform.float.e = d * 2\n\
                       uniform.float.f = f + 1\n\
                       uniform.float.viewWidth = viewWidth / 2\n");
        assert_eq!(out.uniforms.keys().collect::<Vec<_>>(), ["c", "viewWidth"]);
        assert_eq!(out.uniforms["c"], Value::float(3.0));
        // A custom uniform named like a standard one reads the standard value.
        assert_eq!(out.uniforms["viewWidth"], Value::float(960.0));
        let got: Vec<(usize, &str, &str)> =
            out.problems.iter().map(|p| (p.line, p.key.as_str(), p.message.as_str())).collect();
        assert_eq!(got.len(), 4, "{got:?}");
        assert_eq!((got[0].0, got[0].1), (1, "uniform.float.a"));
        assert!(got[0].2.contains("'b' is used before its definition at line 2"), "{}", got[0].2);
        assert_eq!((got[1].0, got[1].1), (4, "variable.float.d"));
        assert!(got[1].2.starts_with("unknown variable 'nope'"), "{}", got[1].2);
        assert_eq!((got[2].0, got[2].1), (5, "uniform.float.e"));
        assert!(got[2].2.contains("'d' has no value: its definition at line 4 failed"), "{}", got[2].2);
        assert_eq!(got[3].0, 6);
        assert!(got[3].2.contains("'f' is used in its own definition"), "{}", got[3].2);
    }

    #[test]
    fn errors_name_the_problem_and_where() {
        assert_eq!(error("foo(1)"), "unknown function 'foo()' (at character 1 of the expression)");
        assert_eq!(error("1 + bar"), "unknown variable 'bar' (at character 5 of the expression)");
        assert!(error("BIOME_PLAINS").contains("unknown biome constant 'BIOME_PLAINS'"));
        assert!(error("1 + true").contains("no operator '+' for float and bool"));
        assert!(error("!1").contains("no operator '!' for a float"));
        assert!(error("-true").contains("no operator '-' for a bool"));
        assert!(error("1 && true").contains("no operator '&&' for float and bool"));
        assert!(error("true < false").contains("no operator '<' for bool and bool"));
        assert!(error("vec2(1, 2) + vec3(1, 2, 3)").contains("no operator '+' for vec2 and vec3"));
        assert!(error("1 == true").contains("no operator '==' for float and bool"));
        assert!(error("if(1, 2, 3)").contains("argument 1 of if() must be a bool condition, found float"));
        assert!(error("if(true, 2, vec2(1, 2))").contains("differ in type: float and vec2"));
        assert!(error("if(true, 2)").contains("odd number of at least 3 arguments"));
        assert!(error("ifb(true, 1, 2)").contains("ifb() selects bools"));
        assert!(error("sin(1, 2)").contains("sin() takes 1 argument, found 2"));
        assert!(error("clamp(1, 2)").contains("clamp() takes 3 arguments, found 2"));
        assert!(error("min(1)").contains("min() takes at least 2 arguments"));
        assert!(error("min(true, false)").contains("min(): operand"));
        assert!(error("sin(true)").contains("sin(): operand is a bool"));
        assert!(error("between(true, 0, 1)").contains("argument 1 of between() must be a float, found bool"));
        assert!(error("in(1)").contains("in() takes a value and at least one candidate"));
        assert!(error("smooth()").contains("smooth() takes 1 to 4 arguments, found 0"));
        assert!(error("smooth(true)").contains("argument 1 of smooth() must be a float"));
        assert!(error("random(1)").contains("random() takes 0 or 2 arguments"));
        assert!(error("vec3(1, 2)").contains("vec3() needs 3 components, found 2"));
        assert!(error("sunAngle.x").contains("'sunAngle' is a float: only vectors and matrices have components"));
        assert!(error("cameraPosition.w").contains("'cameraPosition' is a vec3: it has no component 'w'"));
        assert!(error("cameraPosition.k").contains("'cameraPosition' has no component 'k'"));
        assert!(error("gbufferModelView.4.0").contains("is a mat4: it has no component '4'"));
        assert!(error("gbufferModelView").contains("the expression is a mat4, but the uniform is declared float"));
        assert!(error("tp_TextureMatrix.0.0").contains("is an array (mat4[1])"));
        assert!(error("cameraPosition").contains("the expression is a vec3, but the uniform is declared float"));
        assert!(error("1 < 2").contains("the expression is a bool, but the uniform is declared float"));
        // Parse errors.
        assert_eq!(error(""), "empty expression");
        assert_eq!(error("1 +"), "unexpected end of the expression: a value is missing (at character 4 of the expression)");
        assert!(error("(1 + 2").contains("missing ')' for the '(' at character 1"));
        assert!(error("1 + 2)").contains("unexpected ')' after a complete expression (at character 6"));
        assert!(error("1 2").contains("unexpected number 2 after a complete expression"));
        assert!(error("sin(1 2)").contains("expected ',' or ')' in the arguments of sin()"));
        assert!(error("sin(1,").contains("a value is missing"));
        assert!(error("a = 1").contains("unexpected '=': comparison is '=='"));
        assert!(error("true & false").contains("logical and is '&&'"));
        assert!(error("true | false").contains("logical or is '||'"));
        assert!(error("1 $ 2").contains("unexpected character '$' (at character 3"));
        assert!(error("1.0f").contains("unexpected 'f' after the number 1.0"));
        assert!(error("* 2").contains("expected a value, found '*'"));
        assert!(error("()").contains("expected a value, found ')'"));
        // The line of the entry, not of the file's first line.
        let out = run("# head\n\nuniform.float.ok = 1\nuniform.float.bad = 1 +\n");
        assert_eq!(out.problems.len(), 1);
        assert_eq!(out.problems[0].line, 4);
        assert_eq!(
            out.problems[0].to_string(),
            "shaders.properties:4: uniform.float.bad: unexpected end of the expression: a value is missing (at character 4 of the expression)"
        );
    }

    #[test]
    fn depth_limit_turns_hostile_nesting_into_errors() {
        let n = 100_000;
        let parens = format!("{}1{}", "(".repeat(n), ")".repeat(n));
        assert!(error(&parens).contains(&format!("nested deeper than {MAX_DEPTH} levels")));
        let negations = format!("{}1", "-".repeat(n));
        assert!(error(&negations).contains("nested deeper"));
        let calls = format!("{}1{}", "abs(".repeat(n), ")".repeat(n));
        assert!(error(&calls).contains("nested deeper"));
        // A flat chain is built by a loop, yet its tree is as deep: refused too.
        let chain = vec!["1"; n].join(" + ");
        assert!(error(&chain).contains("nested deeper"));
        let right = format!("{}1", "1 + (".repeat(n)) + &")".repeat(n);
        assert!(error(&right).contains("nested deeper"));
        // Real expressions stay far inside the limit.
        let ok = format!("{}1{}", "(".repeat(50), ")".repeat(50));
        assert_eq!(f(&ok), 1.0);
        assert_eq!(f(&vec!["1"; 150].join(" + ")), 150.0);
    }

    #[test]
    fn garbage_never_panics() {
        for text in [
            "uniform.float.a = ((((",
            "uniform.float.a = ))))",
            "uniform.float.a = ,,,",
            "uniform.float.a = vec2(",
            "uniform.float.a = ....",
            "uniform.float.a = a.b.c.d",
            "uniform.float.a = cameraPosition..x",
            "uniform.float.a = 1e",
            "uniform.float.a = 1e+",
            "uniform.float.a = \\u00",
            "uniform.float.a = \u{00e9}",
            "uniform.vec4.a = gbufferModelView.0.",
            "uniform.float.a = randomInt(5, 5)",
            "uniform.float.a = if(true, 1, true)",
            "uniform.",
            "variable.",
            "uniform.float.a = 1 \\",
            "\\",
            "=",
        ] {
            let out = run(text);
            assert!(out.uniforms.len() + out.problems.len() <= 1, "{text}: {out:?}");
        }
    }
}
