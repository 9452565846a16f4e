//! `--parts K --part P` as a user runs it: `eval` on one part answers its
//! owned triangles with the bytes `eval` on the whole net writes, refuses a
//! triangle another part owns naming the owner, and `info` prints the
//! part's line; `mesh --parts K` writes the same file on one thread and
//! on two; bad input is one clear line, exit 2, nothing on stdout.

mod support;

use support::{assert_clean_failure, loopsurf, loopsurf_with_stdin, scratch, text};

const VIKING: [&str; 4] = ["--example", "viking", "--hard-angle", "30"];

/// Each triangle's part, read from the `part` field `loopsurf partition`
/// writes.
fn owners(k: usize) -> Vec<usize> {
    let vtu = scratch(&format!("owners{k}.vtu"));
    let k = k.to_string();
    let mut args = vec!["partition"];
    args.extend(VIKING);
    args.extend(["--parts", &k, "-o", vtu.to_str().unwrap()]);
    let out = loopsurf(&args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let xml = std::fs::read_to_string(&vtu).unwrap();
    let start = xml.find("Name=\"part\"").expect("a part field");
    let body = &xml[xml[start..].find('>').unwrap() + start + 1..];
    body[..body.find('<').unwrap()]
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

/// `tri v w` lines for `tris`, at the corners, on edges and inside.
fn queries(tris: impl Iterator<Item = usize>) -> String {
    let params = [
        "0 0",
        "1 0",
        "0 1",
        "0.5 0.5",
        "0.25 0",
        "0.2 0.3",
        "0.125 0.625",
    ];
    let mut lines = String::new();
    for t in tris {
        for p in params {
            lines.push_str(&format!("{t} {p}\n"));
        }
    }
    lines
}

fn eval(extra: &[&str], stdin: &str) -> std::process::Output {
    let mut args = vec!["eval"];
    args.extend(VIKING);
    args.extend(extra);
    loopsurf_with_stdin(&args, stdin)
}

#[test]
fn a_part_answers_its_triangles_byte_for_byte_as_the_whole() {
    let k = 5;
    let owners = owners(k);
    let whole = eval(&[], &queries(0..owners.len()));
    assert!(whole.status.success(), "{}", text(&whole.stderr));
    let whole = text(&whole.stdout);
    let whole: Vec<&str> = whole.lines().collect();
    for p in 0..k {
        let mine: Vec<usize> = (0..owners.len()).filter(|&t| owners[t] == p).collect();
        let (ks, ps) = (k.to_string(), p.to_string());
        let out = eval(
            &["--parts", &ks, "--part", &ps],
            &queries(mine.iter().copied()),
        );
        assert!(out.status.success(), "{}", text(&out.stderr));
        let expected: Vec<&str> = mine
            .iter()
            .flat_map(|&t| whole[7 * t..7 * t + 7].iter().copied())
            .collect();
        assert_eq!(
            text(&out.stdout).lines().collect::<Vec<_>>(),
            expected,
            "part {p}"
        );
    }
}

#[test]
fn a_triangle_of_another_part_names_its_owner() {
    let owners = owners(4);
    let t = owners.iter().position(|&p| p == 2).unwrap();
    let out = eval(&["--parts", "4", "--part", "0"], &format!("{t} 0.2 0.3\n"));
    assert_clean_failure(&out, &format!("triangle {t} is owned by part 2"));
    assert!(out.stdout.is_empty());
}

#[test]
fn info_prints_the_part_line() {
    let mut partition = vec!["partition"];
    partition.extend(VIKING);
    partition.extend(["--parts", "3"]);
    let summary = text(&loopsurf(&partition).stdout);
    for (p, line) in summary.lines().skip(1).enumerate() {
        // "part P triangles T halo H"
        let f: Vec<&str> = line.split_whitespace().collect();
        let mut args = vec!["info"];
        args.extend(VIKING);
        let ps = p.to_string();
        args.extend(["--parts", "3", "--part", &ps]);
        let out = loopsurf(&args);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let got = text(&out.stdout);
        let prefix = format!("part {p} of 3: owned {} halo {} bytes ", f[3], f[5]);
        assert!(got.starts_with(&prefix), "{got} (expected {prefix}…)");
        let bytes: usize = got.trim()[prefix.len()..].parse().unwrap();
        assert!(bytes > 0);
    }
    // K = 1 is the whole, with no halo.
    let mut args = vec!["info"];
    args.extend(VIKING);
    args.extend(["--parts", "1", "--part", "0"]);
    let got = text(&loopsurf(&args).stdout);
    assert!(
        got.starts_with("part 0 of 1: owned 1680 halo 0 bytes "),
        "{got}"
    );
    let bytes: usize = got.trim().rsplit(' ').next().unwrap().parse().unwrap();
    assert!(bytes > 0);
}

#[test]
fn bad_part_requests_are_one_line_and_write_nothing() {
    let cases: [(&[&str], &str, &str); 6] = [
        (&["--parts", "0", "--part", "0"], "0 0.2 0.3\n", "K = 0"),
        (
            &["--parts", "1681", "--part", "0"],
            "0 0.2 0.3\n",
            "K = 1681",
        ),
        (
            &["--parts", "3", "--part", "3"],
            "0 0.2 0.3\n",
            "part 3: out of range",
        ),
        (&["--parts", "3"], "0 0.2 0.3\n", "--part"),
        (
            &["--parts", "3", "--part", "0"],
            "1680 0.2 0.3\n",
            "triangle 1680: out of range",
        ),
        (
            &["--parts", "3", "--part", "0", "--interpolate", "solve"],
            "0 0.2 0.3\n",
            "not available with --parts",
        ),
    ];
    for (extra, stdin, needle) in cases {
        let out = eval(extra, stdin);
        assert_clean_failure(&out, needle);
        assert!(out.stdout.is_empty(), "{extra:?}");
    }
    let mut args = vec!["info"];
    args.extend(VIKING);
    args.extend(["--parts", "2", "--part", "5"]);
    let out = loopsurf(&args);
    assert_clean_failure(&out, "part 5: out of range");
    assert!(out.stdout.is_empty());
}

/// `mesh --parts K` writes one mesh, the same file on one thread and on
/// two; `--parts 0` and more parts than control triangles are refused,
/// writing nothing.
#[test]
fn mesh_in_parts_writes_one_mesh_whatever_the_threads() {
    let mut written = Vec::new();
    for threads in ["1", "2"] {
        let out = scratch(&format!("parts-{threads}.obj"));
        let path = out.to_str().unwrap();
        let mut args = vec!["mesh"];
        args.extend(VIKING);
        args.extend(["--size", "0.08", "--parts", "3", "--no-verify", "-o", path]);
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_loopsurf"))
            .args(&args)
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(run.status.success(), "{}", text(&run.stderr));
        written.push(std::fs::read(&out).unwrap());
    }
    assert!(!written[0].is_empty());
    assert!(
        written[0] == written[1],
        "the mesh differs on 1 and 2 threads"
    );
    for (k, needle) in [("0", "0 parts"), ("1681", "K = 1681")] {
        let mut args = vec!["mesh"];
        args.extend(VIKING);
        args.extend(["--size", "0.08", "--parts", k, "-o", "{out}"]);
        support::assert_refused_without_writing(&args, &format!("refused-{k}.obj"), needle);
    }
}
