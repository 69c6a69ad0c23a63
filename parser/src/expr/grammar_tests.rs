//! Grammar tests added with the nom rewrite of the formula parser: precedence of every pair of
//! operators, the byte ranges of tree nodes, the location, help and `bare` flag of errors,
//! blanks, and the order in which errors are met. The expectations follow from the rules in
//! the module documentation (and were checked to hold for the parser before the rewrite too).

use super::*;
use crate::test_context::TestContext;

/// The tree of `text` fully parenthesized, e.g. `((1+2)*3)`.
fn grouping(text: &str) -> String {
    fn show(e: &Expr) -> String {
        match &e.node {
            Node::Number(v) => format!("{v}"),
            Node::Unary(UnOp::Neg, a) => format!("-{}", show(a)),
            Node::Unary(UnOp::Not, a) => format!("!{}", show(a)),
            Node::Binary(op, a, b) => format!("({}{}{})", show(a), symbol(*op), show(b)),
            Node::Math(f, args) => format!("{f:?}({})", args.iter().map(show).collect::<Vec<_>>().join(",")),
            other => format!("{other:?}"),
        }
    }
    show(&parse(text).unwrap_or_else(|e| panic!("{text}: {}", e.message)))
}

const OPERATORS: &[(&str, BinOp)] = &[
    ("||", BinOp::Or),
    ("|^", BinOp::Xor),
    ("&&", BinOp::And),
    ("==", BinOp::Eq),
    ("!=", BinOp::Ne),
    ("<", BinOp::Lt),
    ("<=", BinOp::Le),
    (">", BinOp::Gt),
    (">=", BinOp::Ge),
    ("+", BinOp::Add),
    ("-", BinOp::Sub),
    ("*", BinOp::Mul),
    ("/", BinOp::Div),
    ("%", BinOp::Mod),
    ("^", BinOp::Pow),
];

fn symbol(op: BinOp) -> &'static str {
    OPERATORS.iter().find(|(_, o)| *o == op).unwrap().0
}

fn error_of(text: &str) -> ExprError {
    match evaluate(text, &mut TestContext::new()) {
        Ok(v) => panic!("{text}: expected an error, got {v}"),
        Err(e) => e,
    }
}

/// `(message, offending text, help)` of the error of `text`.
fn located(text: &str) -> (String, &str, Option<String>) {
    let e = error_of(text);
    (e.message, &text[e.offset..e.offset + e.len], e.help)
}

const SYNTAX: &str = "Invalid syntax in variable formula";

#[test]
fn every_pair_of_operators_groups_by_precedence_then_left_to_right() {
    for &(s1, op1) in OPERATORS {
        for &(s2, op2) in OPERATORS {
            let text = format!("1{s1}2{s2}3");
            let want = if op1.precedence() >= op2.precedence() {
                format!("((1{s1}2){s2}3)")
            } else {
                format!("(1{s1}(2{s2}3))")
            };
            assert_eq!(grouping(&text), want, "{text}");
        }
    }
}

#[test]
fn unary_operators_bind_tighter_than_every_binary_operator() {
    for &(s, _) in OPERATORS {
        assert_eq!(grouping(&format!("-1{s}2")), format!("(-1{s}2)"), "-1{s}2");
        assert_eq!(grouping(&format!("!1{s}2")), format!("(!1{s}2)"), "!1{s}2");
        assert_eq!(grouping(&format!("1{s}-2")), format!("(1{s}-2)"), "1{s}-2");
        assert_eq!(grouping(&format!("1{s}!2")), format!("(1{s}!2)"), "1{s}!2");
    }
    assert_eq!(grouping("1*2+3*4^2-5/5%3"), "(((1*2)+(3*(4^2)))-((5/5)%3))");
    assert_eq!(grouping("1||2&&3==4<5+6*7^8"), "(1||(2&&(3==(4<(5+(6*(7^8)))))))");
    assert_eq!(grouping("1^2*3+4<5==6&&7||8"), "(((((((1^2)*3)+4)<5)==6)&&7)||8)");
    assert_eq!(grouping("1+2*3+4"), "((1+(2*3))+4)");
    assert_eq!(grouping("1<2+3<4"), "((1<(2+3))<4)");
    assert_eq!(grouping("2^3^2^2"), "(((2^3)^2)^2)");
    assert_eq!(grouping("-!-1"), "-!-1");
    assert_eq!(grouping("1--1"), "(1--1)");
    assert_eq!(grouping("1-(2-3)"), "(1-(2-3))");
    assert_eq!(grouping("sqrt(1+2)*atan2(3,4^5)"), "(Sqrt((1+2))*Atan2(3,(4^5)))");
    let mut ctx = TestContext::new();
    assert_eq!(evaluate("1*2+3*4^2-5/5%3", &mut ctx).unwrap(), 49.0);
    assert_eq!(evaluate("2^3^2^2", &mut ctx).unwrap(), 4096.0);
    assert_eq!(evaluate("!1==0", &mut ctx).unwrap(), 1.0);
    assert_eq!(evaluate("-1<0", &mut ctx).unwrap(), 1.0);
    assert_eq!(evaluate("1-!0", &mut ctx).unwrap(), 0.0);
    assert_eq!(evaluate("1.5.5.5", &mut ctx).unwrap(), 1.5);
    assert_eq!(evaluate("-.5*4", &mut ctx).unwrap(), -2.0);
    assert_eq!(evaluate("1e+2+1E2", &mut ctx).unwrap(), 200.0);
}

#[test]
fn nodes_cover_their_text() {
    // (formula, the text of the root node)
    for (text, root) in [
        ("  -( 1 + 2 ) * sqrt( 4 )  ", "-( 1 + 2 ) * sqrt( 4 )"),
        ("1*(2)", "1*(2)"),
        ("(1)*2", "(1)*2"),
        ("( 1 )", "1"),
        ("\t!x[3] ", "!x[3]"),
        ("c_t[1][2]+f_a", "c_t[1][2]+f_a"),
        ("count( all , reg )", "count( all , reg )"),
        ("C_x[1][2]", "C_x[1][2]"),
    ] {
        let t = parse(text).unwrap();
        assert_eq!(&text[t.offset..t.offset + t.len], root, "{text:?}");
    }
    let t = parse("atan2( 1 , 2*x )").unwrap();
    let Node::Math(MathFn::Atan2, args) = &t.node else { panic!("{t:?}") };
    assert_eq!([(args[0].offset, args[0].len), (args[1].offset, args[1].len)], [(7, 1), (11, 3)]);
    let t = parse("1 + -2").unwrap();
    let Node::Binary(BinOp::Add, _, b) = &t.node else { panic!("{t:?}") };
    assert_eq!((b.offset, b.len), (4, 2));
    assert_eq!(parse("count( all , (a,b) )").unwrap().node, Node::Function {
        name: "count".into(),
        args: vec!["all".into(), "(a,b)".into()]
    });
    assert_eq!(parse("x[0005]").unwrap().node, Node::AtomValue { keyword: "x".into(), id: Index::Number(5) });
    assert_eq!(parse("v_a[v_]").unwrap().node, Node::Variable { name: "a".into(), index: Some(Index::Variable("".into())) });
}

#[test]
fn blanks_are_those_of_c_isspace() {
    let mut ctx = TestContext::new();
    assert_eq!(evaluate("\x0b1\x0c+\r\n2\t", &mut ctx).unwrap(), 3.0);
    assert_eq!(evaluate("atan2(\t1 ,\n0 )", &mut ctx).unwrap(), std::f64::consts::FRAC_PI_2);
    // a non-ASCII blank is not one, and is located by its bytes
    let text = "1\u{a0}+ 2";
    let e = error_of(text);
    assert_eq!((e.message.as_str(), &text[e.offset..e.offset + e.len]), (SYNTAX, "\u{a0}"));
    assert_eq!(located("é"), (SYNTAX.into(), "é", None));
    assert_eq!(located("1+é").1, "é");
}

#[test]
fn syntax_errors_have_a_location_and_help() {
    let cases: &[(&str, &str, Option<&str>)] = &[
        ("", "", Some("the formula ends where an operand is expected")),
        ("1 +", "", Some("the formula ends where an operand is expected")),
        ("sqrt(1+)", "", Some("the formula ends where an operand is expected")),
        ("+1", "+", Some("LAMMPS formulas have no unary `+`")),
        ("1,2", ",", Some("a comma separates the arguments of a function only")),
        ("1)", ")", Some("this `)` has no matching `(`")),
        ("(1))", ")", Some("this `)` has no matching `(`")),
        ("\"1\"", "\"", Some("quotes are not part of a formula")),
        ("'1'", "'", Some("quotes are not part of a formula")),
        ("(1", "(", Some("this `(` is never closed")),
        ("((1)", "(", Some("this `(` is never closed")),
        ("sqrt(1", "(", Some("this `(` is never closed")),
        ("sqrt((1)", "(", Some("this `(` is never closed")),
        ("2 3", "3", Some("an operator is missing between two operands")),
        ("2 x", "x", Some("an operator is missing between two operands")),
        ("2 .5", ".", Some("an operator is missing between two operands")),
        ("2 (3)", "(", Some("an operator is missing between two operands")),
        ("(1 2)", "2", Some("an operator is missing between two operands")),
        ("atan2(1, 2 3)", "3", Some("an operator is missing between two operands")),
        ("1e5x", "x", Some("an operator is missing between two operands")),
        ("1 = 1", "=", Some("use `==` to compare two values")),
        ("1 ! 1", "!", Some("`!` negates the operand that follows it")),
        ("1 & 1", "&", Some("use `&&` for a logical and")),
        ("1 | 1", "|", Some("use `||` for a logical or, `|^` for exclusive or")),
        ("1 < = 1", "=", None),
        ("1 ! = 1", "!", Some("`!` negates the operand that follows it")),
        ("1 $ 1", "$", None),
        ("#", "#", None),
    ];
    for &(text, at, help) in cases {
        let (message, got_at, got_help) = located(text);
        assert_eq!((message.as_str(), got_at, got_help.as_deref()), (SYNTAX, at, help), "{text:?}");
    }
    // more brackets than the word takes (read without computing: `x[1]` would be computed first)
    for (text, at) in [("x[1][2]", 4), ("v_a[1][2]", 6), ("c_t[1][2][3]", 9)] {
        let e = parse(text).unwrap_err();
        assert_eq!((e.message.as_str(), e.offset, e.len), (SYNTAX, at, 1), "{text}");
    }
}

#[test]
fn index_and_argument_errors_are_bare_and_located() {
    // (formula, message, offending text)
    let cases: &[(&str, &str, &str)] = &[
        ("c_t[12a]", "Non digit character between brackets in variable", "a"),
        ("c_t[1][x]", "Non digit character between brackets in variable", "x"),
        ("x[v_a-1]", "Variable name between brackets must be alphanumeric or underscore characters", "-"),
        ("x[ 1]", "Non digit character between brackets in variable", " "),
        ("v_a[", "Mismatched brackets in variable", "["),
        ("v_a[v_b", "Mismatched brackets in variable", "[v_b"),
        ("f_a[]", "Empty brackets in variable", "[]"),
        ("x[000]", "Index between variable brackets must be positive", "[000]"),
        ("x[99999999999999999999]", "Index 99999999999999999999 between brackets is too large", "99999999999999999999"),
        ("atan2(1,2,3,4,5,6,7)", "Too many args in variable function", "1,2,3,4,5,6,7"),
        ("count( a,b,c,d,e,f,(g,h) ,i)", "Too many args in variable function", " a,b,c,d,e,f,(g,h) ,i"),
    ];
    for &(text, message, at) in cases {
        let e = error_of(text);
        assert_eq!((e.message.as_str(), &text[e.offset..e.offset + e.len]), (message, at), "{text}");
        assert!(e.bare, "{text}: LAMMPS reports this without the variable's name");
    }
    // six arguments are allowed (the error is then the function's own)
    let e = error_of("atan2(1,2,3,4,5,6)");
    assert_eq!((e.message.as_str(), e.bare), ("Invalid math function in variable formula", false));
    // an error in a number is located on the whole number
    assert_eq!(located("2+1e400*3").1, "1e400");
    assert_eq!(located("2+.e5").1, ".e5");
}

#[test]
fn errors_come_in_the_order_lammps_meets_them() {
    // (formula, message, offending text)
    let cases: &[(&str, &str, &str)] = &[
        // the division is computed when `+` ends its right operand, before `(2` is read
        ("1/0 + (2", "Divide by 0 in variable formula", "1/0"),
        ("1/0 + sqrt(1,2,3,4,5,6,7)", "Divide by 0 in variable formula", "1/0"),
        ("1/0 + 2 = 3", "Divide by 0 in variable formula", "1/0"),
        // ... but a bad operator right after its right operand comes first
        ("1/0 = 3", SYNTAX, "="),
        ("1/0^2 3", SYNTAX, "3"),
        // parentheses are matched before their inside is read
        ("(2 + 1/0", SYNTAX, "("),
        ("sqrt(1/0", SYNTAX, "("),
        ("sqrt(1/0,2,3,4,5,6,7)", "Too many args in variable function", "1/0,2,3,4,5,6,7"),
        // the inside of parentheses is read before what follows them
        ("(1/0) 2", "Divide by 0 in variable formula", "1/0"),
        ("(1 2) 1/0", SYNTAX, "2"),
        // operands are computed left to right
        ("sqrt(-1) + 1/0", "Sqrt of negative value in variable formula", "sqrt(-1)"),
        ("2^(1/0)", "Divide by 0 in variable formula", "1/0"),
        ("-(1/0)", "Divide by 0 in variable formula", "1/0"),
        ("!x", "Atom vector in equal-style variable formula", "x"),
        // an operand is computed as soon as it is read, before the text after it
        ("foo 2", "Invalid thermo keyword 'foo' in variable formula", "foo"),
        ("x[1][2]", "Variable atom ID is too large", "x[1]"),
        ("x[0] + (", "Index between variable brackets must be positive", "[0]"),
        ("ternary(1,2,3)+1 2", SYNTAX, "2"),
        ("ternary(0,1,1/0)", "Divide by 0 in variable formula", "1/0"),
    ];
    for &(text, message, at) in cases {
        let e = error_of(text);
        assert_eq!((e.message.as_str(), &text[e.offset..e.offset + e.len]), (message, at), "{text}");
    }
    // the unused branch of ternary() is never read, even when it is not a formula
    let mut ctx = TestContext::new();
    assert_eq!(evaluate("ternary(0, 1 2, 3)", &mut ctx).unwrap(), 3.0);
    assert_eq!(evaluate("ternary(1, 2, (3)(4)) * 2", &mut ctx).unwrap(), 4.0);
    assert_eq!(parse("ternary(1, 2, (3)(4))").unwrap_err().offset, 17);
}

#[test]
fn boolean_errors_are_located() {
    let mut ctx = TestContext::new();
    // (condition, message, offending text)
    let cases: &[(&str, &str, &str)] = &[
        ("1 + 1", "Invalid Boolean syntax in if command", "+"),
        ("1 ==", "Invalid Boolean syntax in if command", ""),
        ("== 1", "Invalid Boolean syntax in if command", "=="),
        ("1 2", "Invalid Boolean syntax in if command", "2"),
        ("(1 == 1", "Invalid Boolean syntax in if command", "("),
        ("é == 1", "Invalid Boolean syntax in if command", "é"),
        // `!` after an operand makes a second value: the whole condition is reported
        ("1 == 2 ! 3", "Invalid Boolean syntax in if command", "1 == 2 ! 3"),
        ("(1 ! 2) == 1", "Invalid Boolean syntax in if command", "1 ! 2"),
        ("abc ! def", "If command boolean not cannot operate on string", "! def"),
        ("abc == 1", "If command boolean is comparing string to number", "abc == 1"),
        ("1 == (abc)", "If command boolean cannot be single string", "abc"),
        ("-e5 == 1", "Invalid number `e5` in if command", "-e5"),
        ("1 == 1e400", "Number `1e400` in if command is out of the range of a double", "1e400"),
    ];
    for &(text, message, at) in cases {
        let e = evaluate_boolean(text, &mut ctx).unwrap_err();
        assert_eq!((e.message.as_str(), &text[e.offset..e.offset + e.len]), (message, at), "{text}");
    }
    let help = |text: &str| evaluate_boolean(text, &mut TestContext::new()).unwrap_err().help;
    assert_eq!(help("1 = 1").as_deref(), Some("use `==` to compare"));
    assert_eq!(help("1 * 1").as_deref(), Some("an `if` condition has no arithmetic; compute it with $(...)"));
    assert_eq!(help("(1").as_deref(), Some("this `(` is never closed"));
    for (text, want) in [("\x0b1\x0c==\t1 ", true), ("-1.5 < -1", true), ("!(a == b)", true), ("1 <= 1 && 2 >= 3", false)] {
        assert_eq!(evaluate_boolean(text, &mut ctx).unwrap(), want, "{text:?}");
    }
}
