//! TeX math → plain Unicode, so that every equation of the book is legible in
//! a terminal: `I\dot{\boldsymbol\Omega} = -\kappa\,\mathbf d` becomes
//! `IΩ̇ = −κ d`, `e^{2t/\sigma}` becomes `e²ᵗ/σ`… where a superscript form
//! exists and `e^(2t/σ)` where it does not.
//!
//! Written here rather than taken from a crate: the crates that turn LaTeX
//! into something else aim at MathML or HTML (for a browser), and the few that
//! aim at Unicode cover symbols but not the accents (Ω̇, Ω̈), fractions and
//! environments the book uses. This converter knows exactly the subset of TeX
//! the book writes and reports every command it does not know (see
//! [`Converted::unknown`]), and a test runs it over every equation in
//! `book/src` and fails on any unknown command or stray backslash.

/// The result of a conversion: the text, possibly several lines (an aligned
/// environment keeps its rows), and the commands that were not understood.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Converted {
    /// Unicode text; rows of `aligned`/`cases` are separated by `\n`.
    pub text: String,
    /// Every `\command` the converter does not know, in order of appearance.
    pub unknown: Vec<String>,
}

/// Converts one TeX math expression (without its `$`, `\[`, `\(` delimiters).
pub fn to_unicode(tex: &str) -> Converted {
    let tokens = tokenize(tex);
    let mut parser = Parser {
        tokens,
        pos: 0,
        unknown: Vec::new(),
    };
    let text = parser.sequence(None);
    let text = tidy(&text);
    Converted {
        text,
        unknown: parser.unknown,
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Command(String),
    Open,
    Close,
    Sup,
    Sub,
    Align,
    /// Source whitespace: ignored in math, kept in `\text{…}`.
    Space,
    Char(char),
}

fn tokenize(tex: &str) -> Vec<Token> {
    let mut out = Vec::new();
    let mut chars = tex.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' => {
                let mut name = String::new();
                match chars.peek() {
                    Some(&n) if n.is_ascii_alphabetic() => {
                        while let Some(&n) = chars.peek() {
                            if n.is_ascii_alphabetic() {
                                name.push(n);
                                chars.next();
                            } else {
                                break;
                            }
                        }
                    }
                    Some(&n) => {
                        name.push(n);
                        chars.next();
                    }
                    None => name.push('\\'),
                }
                let alphabetic = name.chars().all(|c| c.is_ascii_alphabetic());
                out.push(Token::Command(name));
                // As in TeX, the spaces that end a command name are not text.
                if alphabetic {
                    while chars.peek().is_some_and(|c| c.is_whitespace()) {
                        chars.next();
                    }
                }
            }
            '{' => out.push(Token::Open),
            '}' => out.push(Token::Close),
            '^' => out.push(Token::Sup),
            '_' => out.push(Token::Sub),
            '&' => out.push(Token::Align),
            '~' => out.push(Token::Command(" ".into())),
            c if c.is_whitespace() => {
                if out.last() != Some(&Token::Space) {
                    out.push(Token::Space);
                }
            }
            c => out.push(Token::Char(c)),
        }
    }
    out
}

mod symbols;

use symbols::{accent, calligraphic, fraktur, is_plain_font, is_sizing, is_text, symbol};
pub use symbols::{subscript, superscript};

struct Parser {
    tokens: Vec<Token>,
    pos: usize,
    unknown: Vec<String>,
}

impl Parser {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.pos)
    }

    fn next(&mut self) -> Option<Token> {
        let t = self.tokens.get(self.pos).cloned();
        self.pos += 1;
        t
    }

    /// Everything up to the closing brace (or `\end{name}`, or the end).
    fn sequence(&mut self, end_env: Option<&str>) -> String {
        let mut out = String::new();
        while let Some(token) = self.peek().cloned() {
            match token {
                Token::Close => break,
                Token::Command(ref name) if name == "end" => {
                    if end_env.is_some() {
                        break;
                    }
                    self.next();
                    let _ = self.argument_raw();
                }
                Token::Command(ref name) if name == "\\" || name == "cr" => {
                    self.next();
                    // An optional spacing argument: `\\[4pt]`.
                    if self.peek() == Some(&Token::Char('[')) {
                        while let Some(t) = self.next() {
                            if t == Token::Char(']') {
                                break;
                            }
                        }
                    }
                    out.push('\n');
                }
                Token::Align => {
                    self.next();
                    out.push(' ');
                }
                Token::Space => {
                    self.next();
                }
                Token::Sup | Token::Sub => {
                    self.next();
                    let arg = self.argument();
                    let script = if token == Token::Sup {
                        raise(&arg)
                    } else {
                        lower(&arg)
                    };
                    out.push_str(&script);
                }
                _ => {
                    // A named function is set off from a factor before it:
                    // R sin α, φ̇ sin θ sin ψ, never Rsin α.
                    if let Token::Command(name) = &token
                        && is_named_function(name)
                        && ends_with_operand(&out)
                        && !out.ends_with(' ')
                    {
                        out.push(' ');
                    }
                    let atom = self.atom();
                    push_spaced(&mut out, &atom);
                }
            }
        }
        out
    }

    /// True when the next token (past spaces) starts a factor that would
    /// multiply what came before: a letter, a number, a bracket, a named
    /// function, an accent, a font, a fraction, a root.
    fn next_is_factor(&self) -> bool {
        let mut k = self.pos;
        // Past spaces, and the thin spaces TeX puts between factors.
        while matches!(self.tokens.get(k), Some(Token::Space))
            || matches!(self.tokens.get(k), Some(Token::Command(n)) if matches!(n.as_str(), "," | ":" | ";" | "!"))
        {
            k += 1;
        }
        match self.tokens.get(k) {
            Some(Token::Char(c)) => c.is_alphanumeric() || matches!(c, '(' | '['),
            Some(Token::Open) => true,
            Some(Token::Command(name)) => {
                accent(name).is_some()
                    || is_plain_font(name)
                    || matches!(
                        name.as_str(),
                        "frac"
                            | "dfrac"
                            | "tfrac"
                            | "sqrt"
                            | "left"
                            | "mathfrak"
                            | "mathcal"
                            | "mathbb"
                            | "partial"
                            | "nabla"
                    )
                    || symbol(name)
                        .is_some_and(|s| s.chars().next().is_some_and(char::is_alphabetic))
            }
            _ => false,
        }
    }

    /// One argument: a braced group, a command, or a single character.
    fn argument(&mut self) -> String {
        while self.peek() == Some(&Token::Space) {
            self.next();
        }
        match self.peek() {
            Some(Token::Open) => {
                self.next();
                let s = self.sequence(None);
                if self.peek() == Some(&Token::Close) {
                    self.next();
                }
                s
            }
            Some(_) => self.atom(),
            None => String::new(),
        }
    }

    /// A braced argument taken verbatim (environment names, `\text{…}`).
    fn argument_raw(&mut self) -> String {
        while self.peek() == Some(&Token::Space) {
            self.next();
        }
        if self.peek() != Some(&Token::Open) {
            return match self.next() {
                Some(Token::Char(c)) => c.to_string(),
                _ => String::new(),
            };
        }
        self.next();
        let mut depth = 0;
        let mut out = String::new();
        while let Some(t) = self.next() {
            match t {
                Token::Open => {
                    depth += 1;
                    out.push('{');
                }
                Token::Close if depth == 0 => break,
                Token::Close => {
                    depth -= 1;
                    out.push('}');
                }
                Token::Char(c) => out.push(c),
                Token::Space => out.push(' '),
                Token::Sup => out.push('^'),
                Token::Sub => out.push('_'),
                Token::Align => out.push('&'),
                Token::Command(name) => match symbol(&name) {
                    Some(s) => out.push_str(s),
                    None => out.push_str(&name),
                },
            }
        }
        out
    }

    fn atom(&mut self) -> String {
        match self.next() {
            None | Some(Token::Close) => String::new(),
            Some(Token::Open) => {
                let s = self.sequence(None);
                if self.peek() == Some(&Token::Close) {
                    self.next();
                }
                s
            }
            Some(Token::Char('-')) => "−".to_string(),
            Some(Token::Char('\'')) => "′".to_string(),
            Some(Token::Char(c)) => c.to_string(),
            Some(Token::Sup) | Some(Token::Sub) | Some(Token::Align) | Some(Token::Space) => {
                String::new()
            }
            Some(Token::Command(name)) => self.command(&name),
        }
    }

    fn command(&mut self, name: &str) -> String {
        if let Some(mark) = accent(name) {
            let arg = self.argument();
            return with_accent(&arg, mark);
        }
        if let Some(s) = symbol(name) {
            return self.named_symbol(s);
        }
        if is_plain_font(name) {
            return self.argument();
        }
        if is_text(name) {
            return self.argument_raw();
        }
        if is_sizing(name) {
            // The delimiter that follows is printed as itself; `.` is none.
            if self.peek() == Some(&Token::Char('.')) {
                self.next();
            }
            return String::new();
        }
        match name {
            "frac" | "dfrac" | "tfrac" | "cfrac" => self.fraction(),
            "sqrt" => self.root(),
            // `\bfrak` is the book's bold Fraktur (book/macros.txt).
            "mathfrak" | "bfrak" | "mathcal" | "mathscr" | "mathbb" => self.font(name),
            "underbrace" | "overbrace" | "boxed" | "underline" | "phantom_skip" => self.argument(),
            // The book's own macros (book/macros.txt).
            "ret" => lower("ret"),
            // `\sub{x}` is `_{x}` (written so where a `}_` would read as
            // Markdown emphasis).
            "sub" => {
                let arg = self.argument();
                lower(&arg)
            }
            "tag" => format!("    ({})", self.argument_raw()),
            "label" => {
                let _ = self.argument_raw();
                String::new()
            }
            "begin" => self.environment(),
            "not" => {
                let arg = self.argument();
                match arg.as_str() {
                    "=" => "≠".to_string(),
                    "∈" => "∉".to_string(),
                    other => format!("{other}\u{338}"),
                }
            }
            "stackrel" | "overset" => {
                let over = self.argument();
                let base = self.argument();
                format!("{base}{}", raise(&over))
            }
            _ => {
                self.unknown.push(format!("\\{name}"));
                name.to_string()
            }
        }
    }

    /// A symbol; a named function before its argument gets TeX's thin
    /// space, written as a space: sin α, not sinα; sin(α) and sin² stay tight.
    fn named_symbol(&self, s: &str) -> String {
        let named = s.chars().all(|c| c.is_ascii_alphabetic()) && s.len() > 1;
        let tight = matches!(
            self.peek(),
            None | Some(Token::Char('(' | '^' | '_' | ')' | ',' | '.' | ' '))
                | Some(Token::Sup)
                | Some(Token::Sub)
                | Some(Token::Space)
        );
        if named && !tight {
            format!("{s} ")
        } else {
            s.to_string()
        }
    }

    /// `\frac{a}{b}` on one line.
    fn fraction(&mut self) -> String {
        let num = self.argument();
        let den = self.argument();
        // d/dt and dφ/dϑ as written, without brackets; d/dt keeps a space
        // before what it acts on.
        if is_differential(&den) && (is_differential(&num) || is_d(&num)) {
            let text = format!("{}/{}", num.trim(), den.trim());
            return match (is_d(&num), self.next_is_factor()) {
                (true, true) => format!("{text} "),
                // dV/dr r/r would read as one fraction: (dV/dr) r/r.
                (false, true) => format!("({text}) "),
                _ => text,
            };
        }
        // A denominator of more than one symbol is bracketed: 2/(3c³), never
        // 2/3c³, which reads as (2/3)c³.
        let text = format!("{}/{}", wrap(&num), wrap_denominator(&den));
        // A fraction followed by a factor is bracketed as a whole:
        // (Ω₂₀/R) sin α, never Ω₂₀/R sin α.
        if self.next_is_factor() {
            format!("({text})")
        } else {
            text
        }
    }

    /// `\sqrt[n]{x}`.
    fn root(&mut self) -> String {
        let mut index = String::new();
        if self.peek() == Some(&Token::Char('[')) {
            self.next();
            while let Some(t) = self.next() {
                match t {
                    Token::Char(']') => break,
                    Token::Char(c) => index.push(c),
                    _ => {}
                }
            }
        }
        let arg = self.argument();
        let root = match index.as_str() {
            "" | "2" => "√",
            "3" => "∛",
            "4" => "∜",
            _ => return format!("{}√{}", raise(&index), wrap(&arg)),
        };
        format!("{root}{}", wrap(&arg))
    }

    /// The letter fonts Unicode has: Fraktur, script, blackboard bold.
    fn font(&mut self, name: &str) -> String {
        let arg = self.argument();
        arg.chars()
            .map(|c| match name {
                "mathfrak" | "bfrak" => fraktur(c).unwrap_or(c),
                "mathcal" | "mathscr" => calligraphic(c).unwrap_or(c),
                _ => match c {
                    'R' => 'ℝ',
                    'C' => 'ℂ',
                    'N' => 'ℕ',
                    'Z' => 'ℤ',
                    'Q' => 'ℚ',
                    c => c,
                },
            })
            .collect()
    }

    /// `\begin{env} … \end{env}`: matrices on one line, cases and aligned
    /// rows as lines.
    fn environment(&mut self) -> String {
        let env = self.argument_raw();
        if matches!(env.as_str(), "array" | "tabular") {
            let _ = self.argument_raw();
        }
        let body = self.sequence(Some(&env));
        // Consume `\end{env}`.
        if let Some(Token::Command(n)) = self.peek()
            && n == "end"
        {
            self.next();
            let _ = self.argument_raw();
        }
        match env.as_str() {
            "pmatrix" | "bmatrix" | "vmatrix" | "matrix" => {
                let rows: Vec<String> = body
                    .split('\n')
                    .map(|r| r.split_whitespace().collect::<Vec<_>>().join(", "))
                    .collect();
                let (open, close) = match env.as_str() {
                    "bmatrix" => ("[", "]"),
                    "vmatrix" => ("|", "|"),
                    _ => ("(", ")"),
                };
                format!("{open}{}{close}", rows.join("; "))
            }
            "cases" => body
                .split('\n')
                .map(|r| format!("{{ {}", r.trim()))
                .collect::<Vec<_>>()
                .join("\n"),
            _ => body,
        }
    }
}

/// Relations, spaced on both sides as TeX spaces them.
const RELATIONS: [&str; 19] = [
    "=", "≈", "≃", "∼", "≡", "∝", "≤", "≥", "≠", "<", ">", "→", "←", "⇒", "⇐", "⇔", "↦", "≪", "≫",
];

/// Appends an atom, with TeX's spacing: relations get a space on each side,
/// `+` and `−` too when they are binary (after an operand), not when unary.
fn push_spaced(out: &mut String, atom: &str) {
    let binary_capable = atom == "+" || atom == "−" || atom == "±" || atom == "∓";
    if RELATIONS.contains(&atom) || (binary_capable && ends_with_operand(out)) {
        out.push(' ');
        out.push_str(atom);
        out.push(' ');
    } else {
        out.push_str(atom);
    }
}

fn ends_with_operand(s: &str) -> bool {
    match s.trim_end().chars().last() {
        None => false,
        Some(c) => {
            c.is_alphanumeric()
                || is_combining(c)
                || superscript_char(c)
                || subscript_char(c)
                || matches!(
                    c,
                    ')' | ']' | '}' | '|' | '‖' | '′' | '⟩' | '∞' | '.' | '!' | '*' | '†'
                )
        }
    }
}

/// Puts a combining accent on the last letter of `base` (`\dot{\boldsymbol\Omega}` → Ω̇).
fn with_accent(base: &str, mark: char) -> String {
    if base.is_empty() {
        return mark.to_string();
    }
    let mut s = base.to_string();
    s.push(mark);
    s
}

/// Parentheses around a numerator or denominator that is more than one term.
fn wrap(s: &str) -> String {
    let t = s.trim();
    let simple = t.chars().filter(|c| !is_combining(*c)).count() <= 1
        || t.chars().all(|c| {
            c.is_alphanumeric()
                || c == '.'
                || is_combining(c)
                || superscript_char(c)
                || subscript_char(c)
        })
        || (t.starts_with('(') && t.ends_with(')') && balanced_outer(t));
    if simple {
        t.to_string()
    } else {
        format!("({t})")
    }
}

/// A denominator, bracketed unless it is one symbol, a number, already
/// bracketed, or one named function of one symbol (`sin θ`): a product or a
/// sum under a slash is always bracketed.
fn wrap_denominator(s: &str) -> String {
    let t = s.trim();
    let number = t.chars().all(|c| c.is_ascii_digit() || c == '.');
    let function_of_symbol = t.split_once(' ').is_some_and(|(f, arg)| {
        NAMED_FUNCTIONS.contains(&f.trim_end_matches(superscript_char)) && symbol_count(arg) == 1
    });
    if symbol_count(t) <= 1
        || number
        || function_of_symbol
        || (t.starts_with('(') && t.ends_with(')') && balanced_outer(t))
    {
        t.to_string()
    } else {
        format!("({t})")
    }
}

/// Symbols of `s`, not counting accents, sub- and superscripts.
fn symbol_count(s: &str) -> usize {
    s.trim()
        .chars()
        .filter(|c| !is_combining(*c) && !superscript_char(*c) && !subscript_char(*c))
        .count()
}

/// `d`, `d²`, `∂`: the operator of a derivative's numerator.
fn is_d(s: &str) -> bool {
    matches!(s.trim(), "d" | "d²" | "d³" | "∂" | "∂²")
}

/// A differential: d or ∂ (with a power) and one symbol, `dt`, `dϑ`, `dt²`.
fn is_differential(s: &str) -> bool {
    let t = s.trim();
    let rest = t
        .strip_prefix('d')
        .or_else(|| t.strip_prefix('∂'))
        .map(|r| r.trim_start_matches(superscript_char).trim());
    rest.is_some_and(|r| symbol_count(r) == 1)
}

/// The named functions, upright in TeX, set off by spaces here.
const NAMED_FUNCTIONS: [&str; 24] = [
    "sin", "cos", "tan", "cot", "sinh", "cosh", "tanh", "arcsin", "arccos", "arctan", "exp", "ln",
    "log", "det", "dim", "max", "min", "sup", "inf", "lim", "sgn", "Re", "Im", "tr",
];

/// True for the command of a named function (`\sin`, `\ln`, …).
fn is_named_function(name: &str) -> bool {
    NAMED_FUNCTIONS.contains(&name)
}

fn balanced_outer(t: &str) -> bool {
    let mut depth = 0i32;
    let n = t.chars().count();
    for (i, c) in t.chars().enumerate() {
        match c {
            '(' => depth += 1,
            ')' => {
                depth -= 1;
                if depth == 0 && i + 1 < n {
                    return false;
                }
            }
            _ => {}
        }
    }
    depth == 0
}

fn is_combining(c: char) -> bool {
    matches!(c as u32, 0x300..=0x36F | 0x20D0..=0x20FF)
}

fn superscript_char(c: char) -> bool {
    "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁼⁽⁾ⁿⁱᵀ′".contains(c)
}

fn subscript_char(c: char) -> bool {
    "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ⊥∥".contains(c)
}

/// A superscript: Unicode superscript letters when every character has one,
/// otherwise `^x` for one character and `^(…)` for more.
fn raise(s: &str) -> String {
    let t = s.trim();
    if t.is_empty() {
        return String::new();
    }
    if t == "′" || t == "′′" || t == "*" || t == "∗" || t == "†" || t == "ᵀ" {
        return t.to_string();
    }
    let mapped: Option<String> = t.chars().filter(|c| *c != ' ').map(superscript).collect();
    match mapped {
        Some(m) => m,
        None if t.chars().count() == 1 => format!("^{t}"),
        None => format!("^({t})"),
    }
}

/// A subscript, in the same spirit as [`raise`].
fn lower(s: &str) -> String {
    let t = s.trim();
    if t.is_empty() {
        return String::new();
    }
    let mapped: Option<String> = t.chars().filter(|c| *c != ' ').map(subscript).collect();
    match mapped {
        Some(m) => m,
        None if t.chars().count() == 1 => format!("_{t}"),
        None => format!("_({t})"),
    }
}

/// Collapses runs of spaces (TeX ignores them; `\,` and `\quad` made them on
/// purpose, so at most four are kept), puts spaces around `=`, and trims.
fn tidy(s: &str) -> String {
    s.split('\n')
        .map(|line| {
            let mut out = String::new();
            let mut spaces = 0;
            for c in line.chars() {
                if c == ' ' {
                    spaces += 1;
                    continue;
                }
                if spaces > 0 && !out.is_empty() {
                    out.push_str(&" ".repeat(spaces.min(4)));
                }
                spaces = 0;
                out.push(c);
            }
            out
        })
        .filter(|l| !l.trim().is_empty())
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn u(tex: &str) -> String {
        let c = to_unicode(tex);
        assert!(
            c.unknown.is_empty(),
            "unknown commands in {tex:?}: {:?}",
            c.unknown
        );
        c.text
    }

    #[test]
    fn a_named_function_is_spaced_from_its_argument_as_in_tex() {
        assert_eq!(u(r"\sin\alpha"), "sin α");
        assert_eq!(u(r"\sin\tilde\Omega_3 t"), "sin Ω̃₃t");
        assert_eq!(u(r"\sin(\alpha)"), "sin(α)");
        assert_eq!(u(r"\cos^2\theta"), "cos²θ");
    }

    #[test]
    fn named_functions_are_set_off_from_the_factors_around_them() {
        assert_eq!(u(r"\dot\varphi\sin\theta\sin\psi"), "φ\u{307} sin θ sin ψ");
        assert_eq!(u(r"R\sin\alpha"), "R sin α");
        assert_eq!(u(r"(\Omega_1\sin\psi)/\sin\theta"), "(Ω₁ sin ψ)/sin θ");
        assert_eq!(u(r"\ln(m/m_0)"), "ln(m/m₀)");
    }

    #[test]
    fn a_fraction_before_a_factor_is_bracketed_and_a_derivative_is_not() {
        assert_eq!(u(r"\frac{\Omega_{20}}{R}\sin\alpha"), "(Ω₂₀/R) sin α");
        assert_eq!(u(r"\frac{a}{R\sin\alpha}"), "a/(R sin α)");
        assert_eq!(
            u(r"\frac{\Omega_{20}\cos\tilde\psi}{\sin\theta}"),
            "(Ω₂₀ cos ψ\u{303})/sin θ"
        );
        assert_eq!(u(r"\frac{dL}{dt}"), "dL/dt");
        assert_eq!(u(r"\frac{d\varphi}{d\vartheta}"), "dφ/dϑ");
        assert_eq!(u(r"\frac{d}{dt}(x)"), "d/dt (x)");
        assert_eq!(u(r"-\frac{dV}{dr}\frac{\mathbf r}{r}"), "−(dV/dr) r/r");
        assert_eq!(u(r"\frac{2}{3c^3}"), "2/(3c³)");
        assert_eq!(
            u(r"\frac{\Omega_{20}}{\sin\theta}\,\vartheta"),
            "(Ω₂₀/sin θ) ϑ"
        );
    }

    #[test]
    fn greek_accents_and_fonts() {
        assert_eq!(u(r"\dot{\boldsymbol\Omega}"), "Ω\u{307}");
        assert_eq!(u(r"\ddot{\boldsymbol\Omega}"), "Ω\u{308}");
        assert_eq!(u(r"\mathbf d\times\boldsymbol\Omega"), "d×Ω");
        assert_eq!(u(r"\mathfrak d"), "𝔡");
    }

    #[test]
    fn truncated_ale_3_3_keeps_its_braces_and_sign() {
        let s = u(
            r"I\dot{\boldsymbol\Omega} + \boldsymbol\Omega\times I\boldsymbol\Omega =
  -\kappa\{(\mathbf d\times\boldsymbol\Omega)^2\boldsymbol\Omega +
  (\mathbf d\cdot(\boldsymbol\Omega\times\dot{\boldsymbol\Omega}))\,\mathbf d\}",
        );
        assert_eq!(s, "IΩ\u{307} + Ω×IΩ = −κ{(d×Ω)²Ω + (d·(Ω×Ω\u{307})) d}");
    }

    #[test]
    fn scripts_use_unicode_where_it_exists() {
        assert_eq!(u(r"e^{-t/\sigma}"), "e^(−t/σ)");
        assert_eq!(u(r"e^{2t}"), "e²ᵗ");
        assert_eq!(u(r"\Omega_{30}"), "Ω₃₀");
        assert_eq!(u(r"\Omega_\perp^2"), "Ω⊥²");
        assert_eq!(u(r"O^\top"), "Oᵀ");
        assert_eq!(u(r"x^{-1}"), "x⁻¹");
        assert_eq!(u(r"t_{\text{run}}"), "tᵣᵤₙ");
        assert_eq!(u(r"t_{\text{end}}"), "t_(end)");
    }

    #[test]
    fn fractions_and_roots_are_bracketed_only_when_needed() {
        assert_eq!(u(r"\frac{1}{\tau}"), "1/τ");
        assert_eq!(u(r"\frac{2}{3c^3}"), "2/(3c³)");
        assert_eq!(u(r"\frac{2t}{\sigma}"), "2t/σ");
        assert_eq!(
            u(r"\frac{I_1^2}{I_3^2\,\Omega_3^2\,\tau}"),
            "I₁²/(I₃² Ω₃² τ)"
        );
        assert_eq!(u(r"\frac{a+b}{2}"), "(a + b)/2");
        assert_eq!(u(r"\sqrt{1 - \varepsilon^2}"), "√(1 − ε²)");
        assert_eq!(u(r"-\frac{a}{b}"), "−a/b");
        assert_eq!(u(r"\sqrt{x}"), "√x");
    }

    #[test]
    fn aligned_rows_become_lines() {
        let s = u(r"\begin{aligned} a &= b \\ c &= d \end{aligned}");
        assert_eq!(s.lines().count(), 2, "{s:?}");
        assert!(!s.contains('\\'));
    }

    #[test]
    fn unknown_commands_are_reported_not_hidden() {
        let c = to_unicode(r"\frobnicate{x}");
        assert_eq!(c.unknown, vec![r"\frobnicate".to_string()]);
    }
}
