//! `loopsurf partition` as a user runs it: the summary lines, the `part`
//! field of the .vtu, and one clear line with exit 2 on bad input.

mod support;

use std::process::Command;
use support::{assert_clean_failure, assert_refused_without_writing, loopsurf, text};

/// The numbers after each word of a `word n word n ...` line.
fn fields(line: &str) -> Vec<(String, usize)> {
    let words: Vec<&str> = line.split_whitespace().collect();
    words
        .chunks(2)
        .map(|p| (p[0].to_string(), p[1].parse().unwrap()))
        .collect()
}

#[test]
fn partition_prints_the_summary_and_writes_the_part_field() {
    let dir = std::env::temp_dir().join(format!("loopsurf-partition-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let vtu = dir.join("parts.vtu");
    let out = loopsurf(&[
        "partition",
        "--example",
        "viking",
        "--parts",
        "4",
        "-o",
        vtu.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    let head = fields(lines[0]);
    let names: Vec<&str> = head.iter().map(|(w, _)| w.as_str()).collect();
    assert_eq!(names, ["parts", "triangles", "cut", "largest", "halo"]);
    let n = head[1].1;
    assert_eq!(head[0].1, 4);
    assert_eq!(lines.len(), 5);
    // The part lines add up, and the largest part and halo are theirs.
    let parts: Vec<Vec<(String, usize)>> = lines[1..].iter().map(|l| fields(l)).collect();
    for (p, f) in parts.iter().enumerate() {
        assert_eq!(f[0], ("part".to_string(), p));
    }
    assert_eq!(parts.iter().map(|f| f[1].1).sum::<usize>(), n);
    assert_eq!(parts.iter().map(|f| f[1].1).max().unwrap(), head[3].1);
    assert_eq!(parts.iter().map(|f| f[2].1).max().unwrap(), head[4].1);
    // The .vtu holds one part per triangle.
    let xml = std::fs::read_to_string(&vtu).unwrap();
    let start = xml.find("Name=\"part\"").expect("a part field");
    let body = &xml[xml[start..].find('>').unwrap() + start + 1..];
    let values: Vec<usize> = body[..body.find('<').unwrap()]
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(values.len(), n);
    for (p, f) in parts.iter().enumerate() {
        assert_eq!(values.iter().filter(|&&v| v == p).count(), f[1].1);
    }
}

#[test]
fn partition_refuses_bad_part_counts_with_one_line() {
    assert_clean_failure(
        &loopsurf(&["partition", "--example", "tetra", "--parts", "0"]),
        "K = 0",
    );
    assert_clean_failure(
        &loopsurf(&["partition", "--example", "tetra", "--parts", "5"]),
        "K = 5",
    );
    assert_clean_failure(&loopsurf(&["partition", "--example", "tetra"]), "--parts");
    assert_refused_without_writing(
        &[
            "partition",
            "--example",
            "tetra",
            "--parts",
            "2",
            "-o",
            "{out}",
        ],
        "x.obj",
        ".vtu",
    );
    let one = loopsurf(&["partition", "--example", "tetra", "--parts", "1"]);
    assert_eq!(
        text(&one.stdout).lines().next(),
        Some("parts 1 triangles 4 cut 0 largest 4 halo 0")
    );
}

/// The same parts whatever the thread count, from separate processes.
#[test]
fn partition_is_the_same_on_one_and_two_threads() {
    let dir =
        std::env::temp_dir().join(format!("loopsurf-partition-threads-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |threads: &str| {
        let vtu = dir.join(format!("parts{threads}.vtu"));
        let out = Command::new(env!("CARGO_BIN_EXE_loopsurf"))
            .args([
                "partition",
                "--example",
                "viking",
                "--parts",
                "5",
                "-o",
                vtu.to_str().unwrap(),
            ])
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(out.status.success());
        (out.stdout, std::fs::read(&vtu).unwrap())
    };
    assert_eq!(run("1"), run("2"));
}
