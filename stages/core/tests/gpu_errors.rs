//! Device errors come back as `Err` from `catching_errors`, not as wgpu's
//! default panic. Runs on every backend where wgpu finds an adapter (lavapipe
//! and llvmpipe included).
#![cfg(feature = "gpu")]

use liftplan_core::gpu::{Device, catching_errors, open_each_backend};

#[test]
fn a_buffer_the_device_cannot_make_is_an_error_not_a_panic() {
    let devices = open_each_backend(true);
    if devices.is_empty() {
        eprintln!("SKIPPED: no GPU adapter");
    }
    for (backend, opened) in devices {
        check(opened.unwrap_or_else(|e| panic!("{backend:?} has an adapter, but: {e}")));
    }
}

fn check(dev: Device) {
    eprintln!("on {}", dev.name);
    let too_big = dev.device.limits().max_buffer_size.saturating_add(4);
    let got = catching_errors(&dev, || {
        let _ = dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("too big"),
            size: too_big,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        Ok(())
    });
    let err = got.expect_err("a buffer over max_buffer_size must be reported");
    assert!(err.contains("GPU"), "{err}");
    // The device still works afterwards, and work that fails says why itself.
    assert_eq!(catching_errors(&dev, || Ok::<_, String>(7)), Ok(7));
    assert_eq!(catching_errors(&dev, || Err::<(), _>("own reason".to_string())), Err("own reason".to_string()));
}
