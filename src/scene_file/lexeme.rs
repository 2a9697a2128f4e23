//! The tokens of the format as small `nom` parsers: whitespace, numbers in C `strtod`
//! syntax, `%d` type codes, file names and the comment that ends a line (spec §2.2).

use nom::{
    IResult, Parser,
    branch::alt,
    bytes::complete::{tag, tag_no_case, take_till1, take_while},
    character::complete::{char, digit0, digit1, hex_digit0, hex_digit1, one_of},
    combinator::{opt, recognize},
};

/// C's `isspace`: space, tab, newline, vertical tab, form feed, carriage return.
pub fn is_space(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\n' | '\x0b' | '\x0c' | '\r')
}

/// Whitespace that stays on the current line.
fn is_line_space(c: char) -> bool {
    is_space(c) && c != '\n'
}

/// Skips any whitespace, newlines included (what `scanf` does before a conversion).
/// (Written with `str` methods: it runs between every two numbers of a scene.)
pub fn blank(input: &str) -> IResult<&str, &str> {
    // Every space of `is_space` is one ASCII byte, so a byte scan stops where the
    // character scan would, and on a character boundary.
    let spaces = (input.bytes())
        .take_while(|&b| b.is_ascii() && is_space(char::from(b)))
        .count();
    let (blank, rest) = input.split_at(spaces);
    Ok((rest, blank))
}

/// Skips whitespace up to, not past, the end of the line.
pub fn line_blank(input: &str) -> IResult<&str, &str> {
    take_while(is_line_space).parse(input)
}

/// The rest of the line and its newline: the comment after a group's numbers.
pub fn comment(input: &str) -> IResult<&str, &str> {
    // Most lines end right after their numbers: no search needed.
    if let Some(rest) = input.strip_prefix('\n') {
        return Ok((rest, ""));
    }
    Ok(match input.split_once('\n') {
        Some((text, rest)) => (rest, text),
        None => ("", input),
    })
}

/// One whitespace-free token (a file name, or the text quoted in an error).
pub fn token(input: &str) -> IResult<&str, &str> {
    take_till1(is_space).parse(input)
}

/// A number as `strtod` reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NumberToken<'a> {
    /// A finite double.
    Finite(f64),
    /// `inf`, `nan` or a number that overflows a double: valid C, an error here.
    NonFinite(&'a str),
}

fn exponent(marker: &'static str) -> impl FnMut(&str) -> IResult<&str, &str> {
    move |input| recognize((one_of(marker), opt(one_of("+-")), digit1)).parse(input)
}

/// Decimal: `12`, `4.`, `.5`, `1.5e-3`. An `e` with no digits after it is not taken.
fn decimal(input: &str) -> IResult<&str, &str> {
    let mantissa = alt((
        recognize((digit1, opt((char('.'), digit0)))),
        recognize((char('.'), digit1)),
    ));
    recognize((mantissa, opt(exponent("eE")))).parse(input)
}

/// Hexadecimal floating point: `0x1.8p3`. `0x` with no digits is the number 0 then `x`.
fn hexadecimal(input: &str) -> IResult<&str, (&str, &str, Option<&str>)> {
    let (rest, _) = tag_no_case("0x").parse(input)?;
    let (rest, (int, frac)) = alt((
        (
            hex_digit1,
            nom::combinator::map(opt((char('.'), hex_digit0)), |f| f.map_or("", |(_, d)| d)),
        ),
        nom::combinator::map((tag("."), hex_digit1), |(_, d)| ("", d)),
    ))
    .parse(rest)?;
    let (rest, exp) = opt(exponent("pP")).parse(rest)?;
    Ok((rest, (int, frac, exp)))
}

/// `inf`, `infinity`, `nan`, `nan(chars)`, in any case.
fn non_finite_word(input: &str) -> IResult<&str, &str> {
    let nan_payload = (
        char('('),
        take_while(|c: char| c.is_ascii_alphanumeric() || c == '_'),
        char(')'),
    );
    alt((
        tag_no_case("infinity"),
        tag_no_case("inf"),
        recognize((tag_no_case("nan"), opt(nan_payload))),
    ))
    .parse(input)
}

/// Value of a hexadecimal float. Exact for up to 16 significant hex digits; further digits
/// only decide rounding through a sticky bit.
fn hex_value(int: &str, frac: &str, exp: Option<&str>) -> f64 {
    let mut mantissa: u128 = 0;
    let mut shift: i64 = 0; // binary exponent correction
    let mut sticky = false;
    for (i, d) in int.chars().chain(frac.chars()).enumerate() {
        let digit = u128::from(d.to_digit(16).unwrap_or(0));
        if mantissa >> 60 == 0 {
            mantissa = mantissa * 16 + digit;
            if i >= int.len() {
                shift -= 4;
            }
        } else {
            sticky |= digit != 0;
            if i < int.len() {
                shift += 4;
            }
        }
    }
    // Keep the sticky bit in the lowest place so rounding to 53 bits sees it.
    let mantissa = mantissa << 1 | u128::from(sticky);
    shift -= 1;
    let exp: i64 = exp
        .map(|e| {
            e[1..]
                .parse::<i64>()
                .unwrap_or(if e.contains('-') { -100_000 } else { 100_000 })
        })
        .unwrap_or(0);
    let total = exp.saturating_add(shift).clamp(-20_000, 20_000) as i32;
    // Scale in steps that cannot overflow or underflow on the way.
    let mut value = mantissa as f64;
    let mut remaining = total;
    while remaining != 0 {
        let step = remaining.clamp(-1000, 1000);
        value *= 2f64.powi(step);
        remaining -= step;
    }
    value
}

/// The length of the decimal number at the start of `input` (sign, mantissa, exponent),
/// or `None` where it may be another kind of number (hexadecimal, `inf`, `nan`) or none.
#[cfg(test)]
fn plain_decimal(input: &str) -> Option<usize> {
    scan_decimal(input).map(|(length, _)| length)
}

/// 10^0 to 10^22: the powers of ten an f64 holds exactly.
const EXACT_POWERS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The decimal number at the start of `input` (sign, mantissa, exponent): its length, and
/// its value where one rounding gives it; `None` where it may be another kind of number
/// (hexadecimal, `inf`, `nan`) or none. A hand-written scan of exactly what [`decimal`]
/// recognises: most numbers of a scene are decimal, and this is several times faster
/// than the combinators.
///
/// The value is Clinger's fast path: the digits make an integer m of at most 2^53, exact
/// as an f64, and the power of ten p lies within ±22, exact too, so m × 10^p or m / 10^-p
/// is rounded once, correctly, as Rust's own parser rounds. Nearly every number of a
/// scene is that short; the others are left to that parser.
pub fn scan_decimal(input: &str) -> Option<(usize, Option<f64>)> {
    let bytes = input.as_bytes();
    let mut at = usize::from(matches!(bytes.first(), Some(b'+' | b'-')));
    if bytes[at..].starts_with(b"0x") || bytes[at..].starts_with(b"0X") {
        return None;
    }
    // The digits from `at` on, read into `mantissa`; `exact` while it stays at most 2^53
    // (past that it is not used, and may wrap).
    let (mut mantissa, mut exact) = (0u64, true);
    let mut digits = |at: usize| {
        let mut count = 0;
        while let Some(&digit) = bytes.get(at + count).filter(|b| b.is_ascii_digit()) {
            mantissa = mantissa
                .wrapping_mul(10)
                .wrapping_add(u64::from(digit - b'0'));
            exact &= mantissa <= 1 << 53;
            count += 1;
        }
        count
    };
    let whole = digits(at);
    at += whole;
    let mut fraction = 0;
    if bytes.get(at) == Some(&b'.') {
        fraction = digits(at + 1);
        if whole == 0 && fraction == 0 {
            return None;
        }
        at += 1 + fraction;
    }
    if whole == 0 && fraction == 0 {
        return None;
    }
    let mut power = -(fraction as i64);
    if let Some(b'e' | b'E') = bytes.get(at) {
        let sign = usize::from(matches!(bytes.get(at + 1), Some(b'+' | b'-')));
        let from = at + 1 + sign;
        let exponent = bytes[from..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count();
        if exponent > 0 {
            let written: Option<i64> = input[at + 1..from + exponent].parse().ok();
            power = written
                .and_then(|e| power.checked_add(e))
                .unwrap_or(i64::MAX);
            at = from + exponent;
        }
    }
    let mantissa = exact.then_some(mantissa);
    let value = mantissa.zip(EXACT_POWERS.get(power.unsigned_abs() as usize));
    let value = value.map(|(m, &scale)| {
        let magnitude = match power < 0 {
            true => m as f64 / scale,
            false => m as f64 * scale,
        };
        if bytes[0] == b'-' {
            -magnitude
        } else {
            magnitude
        }
    });
    Some((at, value))
}

/// A number in C `strtod` syntax, with an optional sign.
pub fn number(input: &str) -> IResult<&str, NumberToken<'_>> {
    if let Some((length, fast)) = scan_decimal(input) {
        let (text, rest) = input.split_at(length);
        // Rust's own parser is correctly rounded and accepts exactly this syntax.
        let value: f64 = fast.unwrap_or_else(|| text.parse().unwrap_or(f64::NAN));
        let token = match value.is_finite() {
            true => NumberToken::Finite(value),
            false => NumberToken::NonFinite(text),
        };
        return Ok((rest, token));
    }
    let (after_sign, sign) = opt(one_of("+-")).parse(input)?;
    let negative = sign == Some('-');
    if let Ok((rest, (int, frac, exp))) = hexadecimal(after_sign) {
        let value = hex_value(int, frac, exp);
        let text = &input[..input.len() - rest.len()];
        let token = if value.is_finite() {
            NumberToken::Finite(if negative { -value } else { value })
        } else {
            NumberToken::NonFinite(text)
        };
        return Ok((rest, token));
    }
    if let Ok((rest, _)) = non_finite_word(after_sign) {
        return Ok((
            rest,
            NumberToken::NonFinite(&input[..input.len() - rest.len()]),
        ));
    }
    let (rest, _) = decimal(after_sign)?;
    let text = &input[..input.len() - rest.len()];
    // The recogniser above only accepts what Rust's own (correctly rounded) parser accepts.
    let value: f64 = text.parse().unwrap_or(f64::NAN);
    let token = if value.is_finite() {
        NumberToken::Finite(value)
    } else {
        NumberToken::NonFinite(text)
    };
    Ok((rest, token))
}

/// A type code as `%d` reads it: optional sign and digits. Out-of-range values saturate.
pub fn type_code(input: &str) -> IResult<&str, (i64, &str)> {
    let (rest, text) = recognize((opt(one_of("+-")), digit1)).parse(input)?;
    let value = text.parse::<i64>().unwrap_or(if text.starts_with('-') {
        i64::MIN
    } else {
        i64::MAX
    });
    Ok((rest, (value, text)))
}

/// The `QUADRIC` keyword, upper case, followed by whitespace or the end of input.
pub fn quadric_keyword(input: &str) -> IResult<&str, &str> {
    let (rest, word) = tag("QUADRIC").parse(input)?;
    match rest.chars().next() {
        None => Ok((rest, word)),
        Some(c) if is_space(c) => Ok((rest, word)),
        Some(_) => Err(nom::Err::Error(nom::error::Error::new(
            input,
            nom::error::ErrorKind::Tag,
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_decimal_is_rust_s_own_value() {
        // Against `str::parse` (correctly rounded): digits up to 2^53 and beyond, powers
        // of ten at and beyond ±22, signs, zeros, points at either end, exponents.
        let mut texts: Vec<String> = [
            "0",
            "-0",
            "+0.0",
            ".5",
            "5.",
            "-.25e1",
            "9007199254740992",
            "9007199254740993",
            "900719925474099.3",
            "0.1",
            "0.2",
            "0.3",
            "1e22",
            "1e23",
            "1e-22",
            "1e-23",
            "123456789012345678",
            "4.35",
            "-37.762",
            "1E+5",
            "1e-0",
            "000000000001.5",
            "0.000000000000000000001",
            "1.7976931348623157e308",
            "2.2250738585072014e-308",
        ]
        .iter()
        .map(|t| t.to_string())
        .collect();
        let mut state = 0x2026_1125_u64;
        let mut next = |n: u64| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) % n
        };
        for _ in 0..200_000 {
            let mut text = String::new();
            text += ["", "-", "+"][next(3) as usize];
            for _ in 0..next(12) {
                text.push(char::from(b'0' + next(10) as u8));
            }
            if next(4) > 0 {
                text.push('.');
                for _ in 0..next(12) {
                    text.push(char::from(b'0' + next(10) as u8));
                }
            }
            if next(4) == 0 {
                text += &format!("e{}", next(60) as i64 - 30);
            }
            texts.push(text);
        }
        let mut fast = 0;
        for text in texts.iter() {
            if let Some((length, Some(value))) = scan_decimal(text)
                && length == text.len()
            {
                let expected: f64 = text.parse().unwrap();
                assert_eq!(value.to_bits(), expected.to_bits(), "{text}");
                fast += 1;
            }
        }
        assert!(fast > 100_000, "{fast} took the fast path");
    }

    fn value(text: &str) -> (f64, &str) {
        match number(text) {
            Ok((rest, NumberToken::Finite(v))) => (v, rest),
            other => panic!("{text:?} gave {other:?}"),
        }
    }

    #[test]
    fn strtod_forms_of_spec_2_2() {
        assert_eq!(value(".5"), (0.5, ""));
        assert_eq!(value("-.34"), (-0.34, ""));
        assert_eq!(value("4."), (4.0, ""));
        assert_eq!(value("1e-3"), (0.001, ""));
        assert_eq!(value("+2"), (2.0, ""));
        assert_eq!(value("1E+2x"), (100.0, "x"));
    }

    #[test]
    fn number_stops_where_strtod_stops() {
        assert_eq!(value("1e"), (1.0, "e"));
        assert_eq!(value("1e+"), (1.0, "e+"));
        assert_eq!(value("2radius"), (2.0, "radius"));
        assert_eq!(value("1.5.3"), (1.5, ".3"));
        assert_eq!(value("0x"), (0.0, "x"));
        assert_eq!(value("-3.99899 -20"), (-3.99899, " -20"));
    }

    #[test]
    fn hexadecimal_floats_are_exact() {
        assert_eq!(value("0x1.8p1"), (3.0, ""));
        assert_eq!(value("-0X10"), (-16.0, ""));
        assert_eq!(value("0x.8"), (0.5, ""));
        assert_eq!(value("0x1p-1074"), (f64::from_bits(1), ""));
        assert_eq!(value("0x1.fffffffffffffp1023"), (f64::MAX, ""));
        // 0x1.00000000000008 is exactly half way between 1 and the next double: ties to even.
        assert_eq!(value("0x1.00000000000008"), (1.0, ""));
        assert_eq!(value("0x1.000000000000081"), (1.0 + f64::EPSILON, ""));
        // An exponent at the edge of i64 plus extra digits saturates instead of overflowing.
        let huge = number("0x11111111111111111p9223372036854775807").unwrap().1;
        assert!(matches!(huge, NumberToken::NonFinite(_)), "{huge:?}");
        assert_eq!(value("0x11111111111111111p-9223372036854775808"), (0.0, ""));
    }

    #[test]
    fn non_finite_numbers_are_reported_as_such() {
        for text in [
            "inf", "-INF", "Infinity", "nan", "NaN(123)", "1e999", "0x1p2000",
        ] {
            assert!(
                matches!(number(text), Ok((_, NumberToken::NonFinite(_)))),
                "{text}"
            );
        }
        assert_eq!(value("1e-999"), (0.0, ""));
    }

    #[test]
    fn the_fast_decimal_scan_takes_what_the_combinators_take() {
        // Every string of up to 5 characters over the characters that matter.
        let alphabet = ['0', '5', '+', '-', '.', 'e', 'E', 'x', ' '];
        let mut texts = vec![String::new()];
        for _ in 0..5 {
            let longer: Vec<String> = (texts.iter())
                .flat_map(|t| alphabet.iter().map(move |c| format!("{t}{c}")))
                .collect();
            texts.extend(longer);
        }
        for text in &texts {
            let signed = (opt(one_of("+-")), decimal).parse(text.as_str()).ok();
            let slow = signed.map(|(rest, _)| text.len() - rest.len());
            let hex = text.trim_start_matches(['+', '-']).to_ascii_lowercase();
            match plain_decimal(text) {
                Some(length) => assert_eq!(Some(length), slow, "{text:?}"),
                None => assert!(slow.is_none() || hex.starts_with("0x"), "{text:?}"),
            }
        }
    }

    #[test]
    fn words_are_not_numbers() {
        for text in ["x", "-", ".", "+.", "e5", "sphere", ""] {
            assert!(number(text).is_err(), "{text}");
        }
    }

    #[test]
    fn type_codes_read_like_percent_d() {
        assert_eq!(type_code("13 sphere").unwrap(), (" sphere", (13, "13")));
        assert_eq!(type_code("13.5").unwrap().1, (13, "13"));
        assert_eq!(type_code("+14").unwrap().1, (14, "+14"));
        assert_eq!(type_code("99999999999999999999").unwrap().1.0, i64::MAX);
        assert!(type_code("QUADRIC").is_err());
    }

    #[test]
    fn quadric_keyword_is_a_whole_upper_case_word() {
        assert!(quadric_keyword("QUADRIC 1").is_ok());
        assert!(quadric_keyword("QUADRIC").is_ok());
        assert!(quadric_keyword("QUADRICS 1").is_err());
        assert!(quadric_keyword("quadric 1").is_err());
    }
}
