//! The tables of the TeX reader: the commands that are one symbol, the
//! accents, the fonts and the scripts that Unicode has. A table is long
//! because TeX has many symbols; each entry is one line.

/// A TeX accent command and the combining character it becomes.
pub(super) fn accent(name: &str) -> Option<char> {
    Some(match name {
        "dot" => '\u{307}',
        "ddot" => '\u{308}',
        "dddot" => '\u{20DB}',
        "hat" | "widehat" => '\u{302}',
        "vec" => '\u{20D7}',
        "bar" | "overline" => '\u{304}',
        "tilde" | "widetilde" => '\u{303}',
        "check" => '\u{30C}',
        _ => return None,
    })
}

/// A TeX command that is one symbol, and the symbol.
pub(super) fn symbol(name: &str) -> Option<&'static str> {
    match name {
        // Greek, lower case.
        "alpha" => Some("α"),
        "beta" => Some("β"),
        "gamma" => Some("γ"),
        "delta" => Some("δ"),
        "epsilon" => Some("ϵ"),
        "varepsilon" => Some("ε"),
        "zeta" => Some("ζ"),
        "eta" => Some("η"),
        "theta" => Some("θ"),
        "vartheta" => Some("ϑ"),
        "iota" => Some("ι"),
        "kappa" => Some("κ"),
        "lambda" => Some("λ"),
        "mu" => Some("μ"),
        "nu" => Some("ν"),
        "xi" => Some("ξ"),
        "pi" => Some("π"),
        "varpi" => Some("ϖ"),
        "rho" => Some("ρ"),
        "varrho" => Some("ϱ"),
        "sigma" => Some("σ"),
        "varsigma" => Some("ς"),
        "tau" => Some("τ"),
        "upsilon" => Some("υ"),
        "phi" => Some("ϕ"),
        "varphi" => Some("φ"),
        "chi" => Some("χ"),
        "psi" => Some("ψ"),
        "omega" => Some("ω"),
        // Greek, upper case.
        "Gamma" => Some("Γ"),
        "Delta" => Some("Δ"),
        "Theta" => Some("Θ"),
        "Lambda" => Some("Λ"),
        "Xi" => Some("Ξ"),
        "Pi" => Some("Π"),
        "Sigma" => Some("Σ"),
        "Upsilon" => Some("Υ"),
        "Phi" => Some("Φ"),
        "Psi" => Some("Ψ"),
        "Omega" => Some("Ω"),
        // Operators and relations.
        "times" => Some("×"),
        "cdot" => Some("·"),
        "cdots" => Some("⋯"),
        "ldots" | "dots" | "dotsc" | "dotsb" => Some("…"),
        "pm" => Some("±"),
        "mp" => Some("∓"),
        "div" => Some("÷"),
        "ast" => Some("∗"),
        "star" => Some("⋆"),
        "circ" => Some("∘"),
        "bullet" => Some("∙"),
        "wedge" => Some("∧"),
        "otimes" => Some("⊗"),
        "oplus" => Some("⊕"),
        "le" | "leq" => Some("≤"),
        "ge" | "geq" => Some("≥"),
        "ne" | "neq" => Some("≠"),
        "ll" => Some("≪"),
        "gg" => Some("≫"),
        "approx" => Some("≈"),
        "simeq" => Some("≃"),
        "sim" => Some("∼"),
        "equiv" => Some("≡"),
        "propto" => Some("∝"),
        "in" => Some("∈"),
        "notin" => Some("∉"),
        "subset" => Some("⊂"),
        "perp" => Some("⊥"),
        "parallel" => Some("∥"),
        "mid" => Some("∣"),
        "to" | "rightarrow" => Some("→"),
        "leftarrow" | "gets" => Some("←"),
        "Rightarrow" | "implies" => Some("⇒"),
        "Leftarrow" => Some("⇐"),
        "Leftrightarrow" | "iff" => Some("⇔"),
        "leftrightarrow" => Some("↔"),
        "mapsto" => Some("↦"),
        "longrightarrow" => Some("⟶"),
        "uparrow" => Some("↑"),
        "downarrow" => Some("↓"),
        "infty" => Some("∞"),
        "partial" => Some("∂"),
        "nabla" => Some("∇"),
        "sum" => Some("Σ"),
        "prod" => Some("Π"),
        "int" => Some("∫"),
        "oint" => Some("∮"),
        "iint" => Some("∬"),
        "iiint" => Some("∭"),
        "forall" => Some("∀"),
        "exists" => Some("∃"),
        "emptyset" => Some("∅"),
        "hbar" => Some("ℏ"),
        "ell" => Some("ℓ"),
        "prime" => Some("′"),
        "dagger" => Some("†"),
        "top" => Some("ᵀ"),
        "angle" => Some("∠"),
        "langle" => Some("⟨"),
        "rangle" => Some("⟩"),
        "lvert" | "rvert" | "vert" => Some("|"),
        "lVert" | "rVert" | "Vert" => Some("‖"),
        "lfloor" => Some("⌊"),
        "rfloor" => Some("⌋"),
        "lceil" => Some("⌈"),
        "rceil" => Some("⌉"),
        "backslash" => Some("\u{2216}"),
        // Named functions, upright in TeX, plain here.
        "sin" => Some("sin"),
        "cos" => Some("cos"),
        "tan" => Some("tan"),
        "cot" => Some("cot"),
        "sinh" => Some("sinh"),
        "cosh" => Some("cosh"),
        "tanh" => Some("tanh"),
        "arcsin" => Some("arcsin"),
        "arccos" => Some("arccos"),
        "arctan" => Some("arctan"),
        "exp" => Some("exp"),
        "ln" => Some("ln"),
        "log" => Some("log"),
        "det" => Some("det"),
        "dim" => Some("dim"),
        "max" => Some("max"),
        "min" => Some("min"),
        "sup" => Some("sup"),
        "inf" => Some("inf"),
        "lim" => Some("lim"),
        "sgn" => Some("sgn"),
        "Re" => Some("Re"),
        "Im" => Some("Im"),
        "tr" => Some("tr"),
        // Spacing.
        "quad" => Some("  "),
        "qquad" => Some("    "),
        "," | ":" | ";" | " " | "enspace" | "thinspace" => Some(" "),
        "!" | "displaystyle" | "textstyle" | "limits" | "nolimits" | "nonumber" | "notag" => {
            Some("")
        }
        // Escaped characters.
        "{" | "lbrace" => Some("{"),
        "}" | "rbrace" => Some("}"),
        "|" => Some("‖"),
        "%" => Some("%"),
        "$" => Some("$"),
        "#" => Some("#"),
        "&" => Some("&"),
        "_" => Some("_"),
        _ => None,
    }
}

/// The fonts whose argument keeps its letters (bold, upright and the like
/// cannot be shown in every terminal font, and the book's prose names the
/// vectors in words anyway).
pub(super) fn is_plain_font(name: &str) -> bool {
    matches!(
        name,
        "mathbf"
            | "boldsymbol"
            | "bm"
            | "mathrm"
            | "mathit"
            | "mathsf"
            | "mathtt"
            | "operatorname"
            | "mathnormal"
            | "pmb"
    )
}

pub(super) fn is_text(name: &str) -> bool {
    matches!(
        name,
        "text" | "textrm" | "textit" | "textbf" | "mbox" | "hbox"
    )
}

pub(super) fn is_sizing(name: &str) -> bool {
    matches!(
        name,
        "left"
            | "right"
            | "big"
            | "Big"
            | "bigg"
            | "Bigg"
            | "bigl"
            | "bigr"
            | "Bigl"
            | "Bigr"
            | "biggl"
            | "biggr"
            | "middle"
    )
}

pub(super) fn fraktur(c: char) -> Option<char> {
    let table = [
        ('a', '𝔞'),
        ('b', '𝔟'),
        ('c', '𝔠'),
        ('d', '𝔡'),
        ('e', '𝔢'),
        ('f', '𝔣'),
        ('g', '𝔤'),
        ('h', '𝔥'),
        ('i', '𝔦'),
        ('j', '𝔧'),
        ('k', '𝔨'),
        ('l', '𝔩'),
        ('m', '𝔪'),
        ('n', '𝔫'),
        ('o', '𝔬'),
        ('p', '𝔭'),
        ('q', '𝔮'),
        ('r', '𝔯'),
        ('s', '𝔰'),
        ('t', '𝔱'),
        ('u', '𝔲'),
        ('v', '𝔳'),
        ('w', '𝔴'),
        ('x', '𝔵'),
        ('y', '𝔶'),
        ('z', '𝔷'),
    ];
    table.iter().find(|(k, _)| *k == c).map(|(_, v)| *v)
}

pub(super) fn calligraphic(c: char) -> Option<char> {
    Some(match c {
        'A' => '𝒜',
        'B' => 'ℬ',
        'C' => '𝒞',
        'D' => '𝒟',
        'E' => 'ℰ',
        'F' => 'ℱ',
        'H' => 'ℋ',
        'L' => 'ℒ',
        'M' => 'ℳ',
        'N' => '𝒩',
        'O' => '𝒪',
        'P' => '𝒫',
        'R' => 'ℛ',
        'S' => '𝒮',
        'T' => '𝒯',
        _ => return None,
    })
}

pub fn superscript(c: char) -> Option<char> {
    Some(match c {
        '0' => '⁰',
        '1' => '¹',
        '2' => '²',
        '3' => '³',
        '4' => '⁴',
        '5' => '⁵',
        '6' => '⁶',
        '7' => '⁷',
        '8' => '⁸',
        '9' => '⁹',
        '+' => '⁺',
        '-' | '−' => '⁻',
        '=' => '⁼',
        '(' => '⁽',
        ')' => '⁾',
        'a' => 'ᵃ',
        'b' => 'ᵇ',
        'c' => 'ᶜ',
        'd' => 'ᵈ',
        'e' => 'ᵉ',
        'f' => 'ᶠ',
        'g' => 'ᵍ',
        'h' => 'ʰ',
        'i' => 'ⁱ',
        'j' => 'ʲ',
        'k' => 'ᵏ',
        'l' => 'ˡ',
        'm' => 'ᵐ',
        'n' => 'ⁿ',
        'o' => 'ᵒ',
        'p' => 'ᵖ',
        'r' => 'ʳ',
        's' => 'ˢ',
        't' => 'ᵗ',
        'u' => 'ᵘ',
        'v' => 'ᵛ',
        'w' => 'ʷ',
        'x' => 'ˣ',
        'y' => 'ʸ',
        'z' => 'ᶻ',
        'T' => 'ᵀ',
        'ᵀ' => 'ᵀ',
        'A' => 'ᴬ',
        'B' => 'ᴮ',
        'D' => 'ᴰ',
        'E' => 'ᴱ',
        'G' => 'ᴳ',
        'H' => 'ᴴ',
        'I' => 'ᴵ',
        'J' => 'ᴶ',
        'K' => 'ᴷ',
        'L' => 'ᴸ',
        'M' => 'ᴹ',
        'N' => 'ᴺ',
        'O' => 'ᴼ',
        'P' => 'ᴾ',
        'R' => 'ᴿ',
        'U' => 'ᵁ',
        'V' => 'ⱽ',
        'W' => 'ᵂ',
        'β' => 'ᵝ',
        'γ' => 'ᵞ',
        'δ' => 'ᵟ',
        'θ' => 'ᶿ',
        'ϕ' | 'φ' => 'ᵠ',
        'χ' => 'ᵡ',
        '′' => '′',
        '*' | '∗' => '*',
        _ => return None,
    })
}

pub fn subscript(c: char) -> Option<char> {
    Some(match c {
        '0' => '₀',
        '1' => '₁',
        '2' => '₂',
        '3' => '₃',
        '4' => '₄',
        '5' => '₅',
        '6' => '₆',
        '7' => '₇',
        '8' => '₈',
        '9' => '₉',
        '+' => '₊',
        '-' | '−' => '₋',
        '=' => '₌',
        '(' => '₍',
        ')' => '₎',
        'a' => 'ₐ',
        'e' => 'ₑ',
        'h' => 'ₕ',
        'i' => 'ᵢ',
        'j' => 'ⱼ',
        'k' => 'ₖ',
        'l' => 'ₗ',
        'm' => 'ₘ',
        'n' => 'ₙ',
        'o' => 'ₒ',
        'p' => 'ₚ',
        'r' => 'ᵣ',
        's' => 'ₛ',
        't' => 'ₜ',
        'u' => 'ᵤ',
        'v' => 'ᵥ',
        'x' => 'ₓ',
        'β' => 'ᵦ',
        'γ' => 'ᵧ',
        'ρ' => 'ᵨ',
        'ϕ' | 'φ' => 'ᵩ',
        'χ' => 'ᵪ',
        // Marks that read as subscripts when written after a letter.
        '⊥' => '⊥',
        '∥' => '∥',
        '‖' => '‖',
        '*' => '*',
        ',' => ',',
        _ => return None,
    })
}
