//! What a snippet can do, and its limits: each test compiles and runs real
//! snippets against this spintop (the end-to-end tier).

use super::*;
use spintop_server::WarmUp;

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_snippet_runs_against_this_spintop() {
    let s = start("ok", limits());
    let (status, v) = s.run(
        "use spintop::physics::symmetric_top::{self as sym, SymmetricTop};\nlet top = SymmetricTop::figure();\nprintln!(\"sigma = {:.4}\", sym::reduced_decay_time(&top, 0.2));",
    );
    assert_eq!(status, 200, "{v}");
    assert_eq!(v["success"], true, "{v}");
    assert_eq!(v["result"].as_str().unwrap().trim(), "sigma = 156.2500");
    // A failing assertion is reported, with its message.
    let (status, v) = s.run("assert_eq!(1 + 1, 3, \"arithmetic\");");
    assert_eq!(status, 200);
    assert_eq!(v["error"], "failed", "{v}");
    assert!(v["result"].as_str().unwrap().contains("arithmetic"), "{v}");
    // A compile error comes back as the compiler's message.
    let (_, v) = s.run("let x: u32 = \"text\";");
    assert_eq!(v["error"], "compile error", "{v}");
    assert!(
        v["result"].as_str().unwrap().contains("mismatched types"),
        "{v}"
    );
}

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn one_run_at_a_time_a_second_is_told_what_is_busy_and_for_how_long() {
    let s = start("busy", limits());
    // Warm the build first, so that the slow run below is slow by sleeping.
    assert_eq!(s.run("println!(\"warm\");").0, 200);
    let port = s.port;
    let token = s.token.clone();
    let slow = std::thread::spawn(move || {
        request(
            port,
            "POST",
            "/evaluate.json",
            &[("X-Spintop-Token", &token)],
            &body(
                "std::thread::sleep(std::time::Duration::from_millis(2500)); println!(\"slept\");",
            ),
        )
        .unwrap()
    });
    // Once the slow one is taken (it compiles first, then runs), a second
    // is told busy.
    let status = [("X-Spintop-Token", s.token.as_str())];
    assert!(wait_for(Duration::from_secs(60), || {
        let (_, text) = request(s.port, "GET", "/evaluate/status", &status, b"").unwrap();
        text.contains("\"done\":false")
    }));
    let mut answer = serde_json::Value::Null;
    assert!(wait_for(Duration::from_secs(120), || {
        let (status, v) = s.run("println!(\"second\");");
        assert_eq!(status, 429, "{v}");
        answer = v;
        answer["result"].as_str().unwrap().contains("is running")
    }));
    let shown = answer["result"].as_str().unwrap();
    assert!(
        shown.starts_with("busy: another snippet is running ("),
        "{shown}"
    );
    assert!(
        shown.contains("s so far; the time limit is 3 s)"),
        "{shown}"
    );
    let (status, text) = slow.join().unwrap();
    assert_eq!(status, 200, "{text}");
    assert!(text.contains("slept"));
}

/// F2: the time limit covers the whole tree: a `sleep` child, and a busy
/// loop that left the snippet's session and lost its parent, are gone once
/// the time-limit message is shown.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_run_past_the_time_limit_is_killed_with_every_process_it_started() {
    let s = start("time", limits());
    let scratch = s.root.join("scratch");
    let (status, v) = s.run(LEAVES_CHILDREN);
    assert_eq!(status, 200, "{v}");
    assert_eq!(v["error"], "time limit", "{v}");
    let shown = v["result"].as_str().unwrap();
    assert!(
        shown.contains("started both") && shown.contains("time limit"),
        "{shown}"
    );
    assert!(shown.contains("with every process it started"), "{shown}");
    // Killed at the 3 s limit: the note gives the limit it applied.
    assert!(shown.contains("time limit (3 s)"), "{shown}");
    both_gone(&scratch);
}

/// "One run at a time" is one process tree at a time: what a snippet
/// leaves behind when it ends normally goes with it.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn what_a_snippet_leaves_running_is_killed_when_it_ends() {
    let s = start("leftover", limits());
    let scratch = s.root.join("scratch");
    let code = LEAVES_CHILDREN.replace(
        "    loop {\n        std::thread::sleep(std::time::Duration::from_millis(100));\n    }\n",
        "",
    );
    let (status, v) = s.run(&code);
    assert_eq!((status, v["success"].clone()), (200, true.into()), "{v}");
    both_gone(&scratch);
}

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_snippet_runs_in_a_session_of_its_own_under_resource_limits() {
    let s = start("rlimits", limits());
    let (status, v) = s.run(
        "let stat = std::fs::read_to_string(\"/proc/self/stat\").unwrap();\nlet after = &stat[stat.rfind(')').unwrap() + 2..];\nlet sid = after.split(' ').nth(3).unwrap();\nprintln!(\"session {sid}\");\nprint!(\"{}\", std::fs::read_to_string(\"/proc/self/limits\").unwrap());",
    );
    assert_eq!(status, 200, "{v}");
    let shown = v["result"].as_str().unwrap();
    let limit = |name: &str| -> Vec<String> {
        let line = shown
            .lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_else(|| panic!("{name}: {shown}"));
        line[name.len()..]
            .split_whitespace()
            .map(String::from)
            .collect()
    };
    let defaults = Limits::default();
    assert_eq!(limit("Max core file size")[..2], ["0", "0"], "{shown}");
    let memory = defaults.memory.to_string();
    assert_eq!(limit("Max address space")[..2], [memory.clone(), memory]);
    let file = defaults.file_size.to_string();
    assert_eq!(limit("Max file size")[..2], [file.clone(), file]);
    let cpu = defaults.cpu.as_secs();
    assert_eq!(
        limit("Max cpu time")[..2],
        [cpu.to_string(), (cpu + 1).to_string()]
    );
    // Its own session: not this process's.
    let own = std::fs::read_to_string("/proc/self/stat").unwrap();
    let own_sid = own[own.rfind(')').unwrap() + 2..]
        .split(' ')
        .nth(3)
        .unwrap();
    let sid = shown.lines().next().unwrap().trim_start_matches("session ");
    assert_ne!(sid, own_sid, "{shown}");
}

/// The tasks (processes and threads) of real user `uid`, as RLIMIT_NPROC
/// counts them.
fn tasks_of(uid: u32) -> u64 {
    std::fs::read_dir("/proc")
        .unwrap()
        .flatten()
        .filter_map(|e| std::fs::read_to_string(e.path().join("status")).ok())
        .filter_map(|status| {
            let field = |name: &str| {
                status
                    .lines()
                    .find_map(|l| l.strip_prefix(name))
                    .and_then(|v| v.split_whitespace().next())
                    .and_then(|v| v.parse::<u64>().ok())
            };
            (field("Uid:")? == u64::from(uid)).then(|| field("Threads:"))?
        })
        .sum()
}

/// A fork bomb is bounded: a run may start only `Limits::processes` more
/// processes and threads than the reader had when it started (RLIMIT_NPROC,
/// which counts every task of a user, so it is set from the count at the
/// start). The kernel does not hold root to it, so as root the limit is
/// checked; as another user, also that the run cannot pass it.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_run_may_start_only_a_bounded_number_of_processes() {
    let margin = 64;
    let s = start(
        "nproc",
        Limits {
            processes: margin,
            ..limits()
        },
    );
    let uid = rustix::process::getuid().as_raw();
    let enforced = uid != 0;
    let tries = if enforced { margin + 200 } else { 0 };
    let code = format!(
        "print!(\"{{}}\", std::fs::read_to_string(\"/proc/self/limits\").unwrap());\nlet mut kept = Vec::new();\nfor _ in 0..{tries} {{\n    match std::thread::Builder::new().stack_size(64 << 10).spawn(|| std::thread::sleep(std::time::Duration::from_secs(2))) {{\n        Ok(t) => kept.push(t),\n        Err(_) => break,\n    }}\n}}\nprintln!(\"started {{}}\", kept.len());"
    );
    let before = tasks_of(uid);
    let (status, v) = s.run(&code);
    let after = tasks_of(uid);
    assert_eq!(status, 200, "{v}");
    let shown = v["result"].as_str().unwrap();
    let line = shown
        .lines()
        .find(|l| l.starts_with("Max processes"))
        .unwrap_or_else(|| panic!("{shown}"));
    let values: Vec<u64> = line["Max processes".len()..]
        .split_whitespace()
        .take(2)
        .map(|v| v.parse().unwrap_or(u64::MAX))
        .collect();
    assert_eq!(values[0], values[1], "{line}");
    // Other tests (and other users' builds) start and end tasks meanwhile.
    let slack = 2000;
    let (low, high) = (before.min(after), before.max(after));
    assert!(
        values[0] >= margin + low.saturating_sub(slack) && values[0] <= margin + high + slack,
        "{line}: this user had {before} to {after} tasks"
    );
    if enforced {
        let started: u64 = shown
            .lines()
            .find_map(|l| l.strip_prefix("started "))
            .unwrap()
            .parse()
            .unwrap();
        assert!(started < tries, "{shown}");
    }
}

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_snippet_cannot_take_more_memory_than_its_limit() {
    let s = start("memory", limits());
    // 8 GiB of address space, never touched: granted without a limit.
    let (status, v) = s.run(
        "let v: Vec<u8> = Vec::with_capacity(8 << 30);\nprintln!(\"granted {} GiB\", v.capacity() >> 30);",
    );
    assert_eq!(status, 200, "{v}");
    assert_eq!(v["success"], false, "{v}");
    let shown = v["result"].as_str().unwrap();
    assert!(shown.contains("memory allocation of"), "{shown}");
    assert!(shown.contains("memory limit is 4096 MiB"), "{shown}");
}

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_busy_loop_is_stopped_at_its_cpu_time() {
    let s = start(
        "cpu",
        Limits {
            run: Duration::from_secs(60),
            cpu: Duration::from_secs(1),
            ..limits()
        },
    );
    let (status, v) = s.run("let mut x = 0u64; loop { x = std::hint::black_box(x + 1); }");
    assert_eq!(status, 200, "{v}");
    assert_eq!(v["error"], "failed", "{v}");
    let shown = v["result"].as_str().unwrap();
    assert!(shown.contains("used its 1 s of CPU time"), "{shown}");
}

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_snippet_cannot_write_a_file_past_its_limit() {
    let s = start(
        "fsize",
        Limits {
            file_size: 1 << 20,
            ..limits()
        },
    );
    let (status, v) =
        s.run("std::fs::write(\"big\", vec![0u8; 2 << 20]).unwrap();\nprintln!(\"wrote it\");");
    assert_eq!(status, 200, "{v}");
    let shown = v["result"].as_str().unwrap();
    assert!(!shown.contains("wrote it"), "{shown}");
    assert!(shown.contains("past the 1 MiB limit"), "{shown}");
    let written = std::fs::metadata(s.root.join("scratch/big")).unwrap().len();
    assert!(written <= 1 << 20, "{written}");
}

/// A compile-time loop holds ▶ no longer than the warm compile limit, which
/// holds once the background build has built the scratch project; its
/// compiler is killed with cargo, and a ▶ meanwhile says what is busy.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_compile_time_loop_is_stopped_at_the_compile_limit_with_its_compiler() {
    let s = start(
        "compile",
        Limits {
            compile_warm: Duration::from_secs(8),
            ..limits()
        },
    );
    s.server.warm_up();
    assert!(
        wait_for(Duration::from_secs(900), || matches!(
            s.server.warm_up_state(),
            WarmUp::Ready { .. } | WarmUp::Failed { .. }
        )),
        "the background build did not end"
    );
    let state = s.server.warm_up_state();
    assert!(matches!(state, WarmUp::Ready { .. }), "{state:?}");
    let port = s.port;
    let token = s.token.clone();
    let looping = std::thread::spawn(move || {
        request(
            port,
            "POST",
            "/evaluate.json",
            &[("X-Spintop-Token", &token)],
            &body(
                "#![allow(long_running_const_eval)]\nconst N: u64 = { let mut i = 0u64; while i < u64::MAX { i += 1; } i };\nfn main() { println!(\"{N}\"); }",
            ),
        )
        .unwrap()
    });
    // The compiler of this scratch project (its folder is the compiler's),
    // while it loops.
    let scratch = s.root.join("scratch");
    let me = std::process::id() as i32;
    let mut compilers = Vec::new();
    assert!(wait_for(Duration::from_secs(60), || {
        compilers = descendants(me)
            .into_iter()
            .filter(|&p| {
                cmdline(p).contains("spintop_snippet_")
                    && std::fs::read_link(format!("/proc/{p}/cwd")).ok().as_deref()
                        == Some(scratch.as_path())
            })
            .collect();
        !compilers.is_empty()
    }));
    let (status, v) = s.run("println!(\"meanwhile\");");
    assert_eq!(status, 429, "{v}");
    let shown = v["result"].as_str().unwrap();
    assert!(shown.contains("is compiling ("), "{shown}");
    assert!(shown.contains("the compile limit is 8 s)"), "{shown}");
    let (status, text) = looping.join().unwrap();
    assert_eq!(status, 200, "{text}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["error"], "compile time limit", "{v}");
    for pid in compilers {
        assert!(!alive(pid), "the compiler {pid} outlived the compile limit");
    }
}

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn output_past_its_limit_is_truncated_with_a_note() {
    let s = start(
        "output",
        Limits {
            output_bytes: 4096,
            ..limits()
        },
    );
    let (_, v) = s.run("for i in 0..100_000 { println!(\"line {i}\"); }");
    let shown = v["result"].as_str().unwrap();
    assert!(
        shown.contains("[output truncated"),
        "{}",
        &shown[shown.len() - 200..]
    );
    assert!(shown.len() < 4096 + 200, "{}", shown.len());
}

#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_long_run_answers_pending_and_its_status_follows_it() {
    let s = start(
        "pending",
        Limits {
            answer_within: Duration::from_millis(0),
            ..limits()
        },
    );
    let (status, v) = s.run("println!(\"done at last\");");
    assert_eq!(status, 202, "{v}");
    assert_eq!(v["pending"], true);
    let token = [("X-Spintop-Token", s.token.as_str())];
    let mut last = serde_json::Value::Null;
    for _ in 0..2400 {
        let (status, text) = request(s.port, "GET", "/evaluate/status", &token, b"").unwrap();
        assert_eq!(status, 200);
        last = serde_json::from_str(&text).unwrap();
        if last["done"] == true {
            break;
        }
        std::thread::sleep(Duration::from_millis(250));
    }
    assert_eq!(last["done"], true, "{last}");
    assert_eq!(last["result"].as_str().unwrap().trim(), "done at last");
}

/// A warm run that takes longer than the answer time is answered "pending"
/// with what it is doing, not with the first, cold build's minutes.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_warm_run_past_the_answer_time_does_not_claim_a_cold_build() {
    let s = start(
        "pendingwarm",
        Limits {
            answer_within: Duration::from_millis(300),
            ..limits()
        },
    );
    s.server.warm_up();
    assert!(wait_for(Duration::from_secs(600), || matches!(
        s.server.warm_up_state(),
        WarmUp::Ready { .. }
    )));
    let (status, v) = s.run("std::thread::sleep(std::time::Duration::from_millis(2000));");
    assert_eq!(status, 202, "{v}");
    let shown = v["result"].as_str().unwrap();
    assert!(!shown.contains("first run"), "{shown}");
    assert!(
        shown.starts_with("compiling…") || shown.starts_with("running… (its time limit is 3 s)"),
        "{shown}"
    );
}
