//! GPU access for the stages that have a wgpu twin (depth map, pictures).
//!
//! Only opening a device lives here, so every stage picks adapters the same way
//! and `[gpu] use` means the same thing everywhere. What runs on the device
//! belongs to each stage; nothing here computes anything.

use serde::{Deserialize, Serialize};

/// Whether to use a GPU (`[gpu] use` in the project file).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum GpuUse {
    /// A hardware adapter when there is one, else the CPU path.
    #[default]
    Auto,
    /// Always the CPU path.
    Never,
    /// Any adapter, software ones included; an error without one.
    Require,
}

/// An open device and its queue.
pub struct Device {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// Adapter name and backend, for reports.
    pub name: String,
}

/// Opens the first adapter wgpu offers, or says why there is none. A software
/// adapter (lavapipe, llvmpipe: slower than the CPU paths) is taken only when
/// `allow_software` is set, as `require` and the twin tests do to exercise the
/// GPU code anywhere.
pub fn open_device(allow_software: bool) -> Result<Device, String> {
    let adapter = first_adapter(wgpu::InstanceDescriptor::new_without_display_handle_from_env())
        .map_err(|e| format!("no GPU adapter: {e}"))?;
    open_adapter(&adapter, allow_software)
}

/// A device on each backend that has an adapter (Vulkan, Metal, DirectX 12,
/// OpenGL; only those `WGPU_BACKEND` names where it is set), each named, or
/// why it did not open. For the twin tests: the backends' shader compilers
/// differ, and so can what a shader does on the same adapter (Mesa's
/// lavapipe runs loops differently through Vulkan and through OpenGL).
pub fn open_each_backend(allow_software: bool) -> Vec<(wgpu::Backend, Result<Device, String>)> {
    let wanted = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
    [wgpu::Backend::Vulkan, wgpu::Backend::Metal, wgpu::Backend::Dx12, wgpu::Backend::Gl]
        .into_iter()
        .filter(|&b| wanted.contains(wgpu::Backends::from(b)))
        .filter_map(|b| {
            let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
            descriptor.backends = wgpu::Backends::from(b);
            let adapter = first_adapter(descriptor).ok()?;
            Some((b, open_adapter(&adapter, allow_software)))
        })
        .collect()
}

/// The adapter wgpu offers first on the backends of `descriptor`.
fn first_adapter(descriptor: wgpu::InstanceDescriptor) -> Result<wgpu::Adapter, wgpu::RequestAdapterError> {
    let instance = wgpu::Instance::new(descriptor);
    pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))
}

fn open_adapter(adapter: &wgpu::Adapter, allow_software: bool) -> Result<Device, String> {
    let info = adapter.get_info();
    if info.device_type == wgpu::DeviceType::Cpu && !allow_software {
        return Err(format!("only a software adapter ({}) is available", info.name));
    }
    // The adapter's own limits, not wgpu's portable defaults: a depth map of
    // tens of millions of points wants storage buffers of gigabytes, which
    // every desktop GPU binds (the defaults stop at 128 MiB).
    let descriptor = wgpu::DeviceDescriptor { required_limits: adapter.limits(), ..Default::default() };
    let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
        .map_err(|e| format!("GPU device on {}: {e}", info.name))?;
    Ok(Device { device, queue, name: format!("{} ({:?})", info.name, info.backend) })
}

/// The device `[gpu] use` asks for: `never` none; `auto` a hardware adapter if
/// one opens (else none, logged); `require` any adapter, or an error saying why
/// there is none. `what` names the work for the log ("depth map", "pictures").
pub fn open_for(use_: GpuUse, what: &str) -> Result<Option<Device>, String> {
    match use_ {
        GpuUse::Never => Ok(None),
        GpuUse::Auto => Ok(open_device(false).map_err(|e| tracing::info!("{what} on the CPU: {e}")).ok()),
        GpuUse::Require => open_device(true).map(Some).map_err(|e| format!("[gpu] use = \"require\" but {e}")),
    }
}

/// Runs `work` on `dev` with the device's out-of-memory and validation errors
/// caught: they come back as `Err` instead of reaching wgpu's default handler,
/// which panics. Work that fails on its own says why; otherwise the first
/// device error does.
pub fn catching_errors<T>(dev: &Device, work: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    let out_of_memory = dev.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let invalid = dev.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let done = work();
    let invalid = pollster::block_on(invalid.pop());
    let out_of_memory = pollster::block_on(out_of_memory.pop());
    match (done, out_of_memory.or(invalid)) {
        (Err(why), _) => Err(why),
        (Ok(_), Some(e)) => Err(format!("GPU ({}): {e}", dev.name)),
        (Ok(v), None) => Ok(v),
    }
}

/// Waits for the device and copies `bytes` bytes of `src` from byte `offset`
/// back to the host (both multiples of 4).
pub fn read_back(dev: &Device, src: &wgpu::Buffer, offset: u64, bytes: u64) -> Result<Vec<u8>, String> {
    read_back_with(dev, src, offset, bytes, <[u8]>::to_vec)
}

/// [`read_back`], handing the bytes to `read` where they are mapped instead
/// of copying them out: a reader that decodes them (a depth map's hundreds of
/// megabytes of intervals) copies them once.
pub fn read_back_with<T>(
    dev: &Device,
    src: &wgpu::Buffer,
    offset: u64,
    bytes: u64,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, String> {
    let staging = dev.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read back"),
        size: bytes.max(4),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut enc = dev.device.create_command_encoder(&Default::default());
    if bytes > 0 {
        enc.copy_buffer_to_buffer(src, offset, &staging, 0, bytes);
    }
    dev.queue.submit([enc.finish()]);
    map_read_with(dev, &staging, bytes, read)
}

/// Maps a `MAP_READ` buffer and copies its first `bytes` bytes out.
pub fn map_read(dev: &Device, staging: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>, String> {
    map_read_with(dev, staging, bytes, <[u8]>::to_vec)
}

/// Maps a `MAP_READ` buffer and hands its first `bytes` bytes to `read`.
fn map_read_with<T>(
    dev: &Device,
    staging: &wgpu::Buffer,
    bytes: u64,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, String> {
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    dev.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| format!("GPU poll: {e}"))?;
    rx.recv().map_err(|e| e.to_string())?.map_err(|e| format!("GPU read back: {e}"))?;
    let data = slice.get_mapped_range().map_err(|e| format!("GPU read back: {e:?}"))?;
    let out = read(&data[..bytes as usize]);
    drop(data);
    staging.unmap();
    Ok(out)
}
