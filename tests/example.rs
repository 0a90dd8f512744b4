//! `examples/regression_test.rs`, the public API as a user's own test uses it, runs and passes.
//! `cargo test` builds the examples beside the tests; this runs the built binary.

use std::process::Command;

#[test]
fn the_regression_test_example_passes() {
    let deps = std::env::current_exe().unwrap();
    let profile = deps.parent().unwrap().parent().unwrap();
    let example = profile.join("examples").join("regression_test");
    assert!(
        example.is_file(),
        "{} is built by `cargo test`",
        example.display()
    );
    let output = Command::new(&example).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("regression test passed"), "{stdout}");
    assert_eq!(stdout.matches("(relative ").count(), 6, "{stdout}");
}
