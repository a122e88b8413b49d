//! Device errors come back as `Err` from `catching_errors`, not as wgpu's
//! default panic. Runs where wgpu finds an adapter (lavapipe included).
#![cfg(feature = "gpu")]

use liftplan_core::gpu::{catching_errors, open_device};

#[test]
fn a_buffer_the_device_cannot_make_is_an_error_not_a_panic() {
    let dev = match open_device(true) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("SKIPPED: no GPU adapter: {e}");
            return;
        }
    };
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
