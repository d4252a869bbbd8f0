//! `build --json` reports the peak resident memory of the build (VmHWM, issue 22).

use std::path::Path;
use std::process::Command;

#[test]
fn build_json_reports_the_peak_memory() {
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp");
    let dir = std::env::temp_dir().join(format!("flexbody-mem-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("conrod.flexbody");
    let o = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("build")
        .arg(&model)
        .args([
            "--interface",
            "BIG_END,SMALL_END",
            "--modes",
            "8",
            "--units",
            "si",
            "--json",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    if !Path::new("/proc/self/status").exists() {
        assert!(v["peak_memory_mb"].is_null());
        return;
    }
    let mb = v["peak_memory_mb"]
        .as_f64()
        .expect("peak_memory_mb in the report");
    // 18.6k dofs: K, M (full, ~1.4 M non-zeros each) and L alone are tens of MB; far below 4 GB
    assert!(mb > 20.0 && mb < 4096.0, "peak {mb} MB");
}
