//! Instance, adapter and device. A hardware adapter is preferred; without one the software
//! adapters are used (lavapipe on Vulkan, then llvmpipe through GL), and the choice is logged.
//!
//! wgpu's default uncaptured-error handler panics. We install our own: errors are logged and
//! collected, and [`Gpu::check`] turns them into an [`Error::Gpu`] after a frame, so a
//! validation error ends a command with a message instead of a panic.

use std::sync::{Arc, Mutex};

use crate::{Error, Result};

/// The device and everything needed to create resources on it.
pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    /// Whether the device was created with timestamp queries (usable inside encoders).
    pub timestamps: bool,
    errors: Arc<Mutex<Vec<String>>>,
}

/// Order of preference among adapters: hardware first, software last.
fn preference(info: &wgpu::AdapterInfo) -> (u8, u8) {
    let kind = match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Cpu => 3,
        wgpu::DeviceType::Other => 4,
    };
    let backend = match info.backend {
        wgpu::Backend::Vulkan | wgpu::Backend::Metal | wgpu::Backend::Dx12 => 0,
        _ => 1,
    };
    (kind, backend)
}

/// The message to show when no adapter exists at all.
pub const NO_ADAPTER_HELP: &str = "no GPU adapter found (not even a software one); \
on Debian/Ubuntu install Mesa's software drivers: `sudo apt-get install mesa-vulkan-drivers` (Vulkan) \
or `sudo apt-get install libegl-mesa0 libgl1-mesa-dri` (OpenGL)";

/// wgpu's flags from the environment, without debug labels unless `WGPU_DEBUG=1` asks for them:
/// Mesa 22.3's lavapipe (Debian bookworm's software Vulkan) crashes in
/// `vkCmdBeginDebugUtilsLabelEXT`, which wgpu calls for every debug group when labels are on.
pub fn instance_descriptor(mut desc: wgpu::InstanceDescriptor) -> wgpu::InstanceDescriptor {
    if std::env::var_os("WGPU_DEBUG").is_none() {
        desc.flags.remove(wgpu::InstanceFlags::DEBUG);
    }
    desc
}

impl Gpu {
    /// A device for offscreen work: capture, bench, report and the tests.
    pub fn headless() -> Result<Self> {
        let instance =
            wgpu::Instance::new(instance_descriptor(wgpu::InstanceDescriptor::new_without_display_handle_from_env()));
        Self::from_instance(instance, None)
    }

    /// A headless device on the given backends only (the backend comparison test).
    pub fn headless_on(backends: wgpu::Backends) -> Result<Self> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        descriptor.backends = backends;
        Self::from_instance(wgpu::Instance::new(instance_descriptor(descriptor)), None)
    }

    /// Picks the best adapter that can present to `surface` (or any, when `None`) and opens a
    /// device with the adapter's own limits, so large targets are possible where the hardware
    /// has them; sizes are checked against those limits before textures are created.
    pub fn from_instance(instance: wgpu::Instance, surface: Option<&wgpu::Surface<'_>>) -> Result<Self> {
        let mut adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()));
        if let Some(surface) = surface {
            adapters.retain(|a| a.is_surface_supported(surface));
        }
        if adapters.is_empty() {
            return Err(Error::Gpu(NO_ADAPTER_HELP.into()));
        }
        adapters.sort_by_key(|a| preference(&a.get_info()));
        let adapter = adapters.swap_remove(0);
        let info = adapter.get_info();
        log::info!("adapter: {} ({:?}, {:?}, driver {})", info.name, info.backend, info.device_type, info.driver);

        let wanted = wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS;
        let features = adapter.features() & wanted;
        let timestamps = features.contains(wanted);
        // What this backend lacks degrades, each with one line: no per-pass GPU times (wall time
        // instead), depth read back through a copy pass.
        if !timestamps {
            log::info!(
                "{:?} on {} has no timestamp queries: timings are synchronised wall time",
                info.backend,
                info.name
            );
        }
        if !adapter.get_downlevel_capabilities().flags.contains(wgpu::DownlevelFlags::DEPTH_TEXTURE_AND_BUFFER_COPIES) {
            log::debug!("{:?} cannot copy depth to a buffer: depth is read back through a copy pass", info.backend);
        }
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("ssdo_device"),
            required_features: features,
            required_limits: adapter.limits(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::MemoryUsage,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| Error::Gpu(format!("could not open a device on {}: {e}", info.name)))?;

        seamless_cube_maps(&device);

        let errors = Arc::new(Mutex::new(Vec::new()));
        let sink = errors.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            let message = e.to_string();
            log::error!("wgpu: {message}");
            if let Ok(mut list) = sink.lock() {
                list.push(message);
            }
        }));
        device.set_device_lost_callback(|reason, message| {
            log::error!("GPU device lost ({reason:?}): {message}");
        });

        Ok(Self { instance, adapter, device, queue, info, timestamps, errors })
    }

    /// A one-line description of the adapter, for logs and reports.
    pub fn describe(&self) -> String {
        format!("{} ({:?}, {})", self.info.name, self.info.backend, self.info.driver)
    }

    /// Whether this is a CPU rasteriser (lavapipe, llvmpipe); reports say so beside timings.
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// Returns the first GPU error reported since the last check, if any.
    pub fn check(&self) -> Result<()> {
        let mut list = self.errors.lock().map_err(|_| Error::Gpu("error log poisoned".into()))?;
        let first = list.drain(..).next();
        match first {
            Some(first) => Err(Error::Gpu(first)),
            None => Ok(()),
        }
    }

    /// Fails with a clear message when a 2D target of `width` x `height` exceeds the device.
    pub fn check_size(&self, width: u32, height: u32) -> Result<()> {
        let max = self.device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 {
            return Err(Error::Setting(format!("size {width}x{height}: both sides must be at least 1")));
        }
        if width > max || height > max {
            return Err(Error::Setting(format!(
                "size {width}x{height} exceeds this adapter's largest 2D texture ({max}x{max})"
            )));
        }
        Ok(())
    }

    /// Blocks until the queue is idle.
    pub fn wait(&self) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| Error::Gpu(format!("waiting for the GPU: {e}")))
    }
}

/// Turns on seamless cube-map filtering where `device` runs on desktop OpenGL, which filters each
/// face apart unless told otherwise (Vulkan and OpenGL ES always filter across the faces):
/// without it the sky's face edges are hard seams, in the background and in every level of the
/// sky the sampling passes read. wgpu does not set it; nothing else on the context changes it.
fn seamless_cube_maps(device: &wgpu::Device) {
    use glow::HasContext;
    // SAFETY: the context is used only while its lock is held, and the one state set is none
    // that wgpu tracks.
    unsafe {
        if let Some(hal) = device.as_hal::<wgpu::hal::api::Gles>() {
            let gl = hal.context().lock();
            if !gl.version().is_embedded {
                gl.enable(glow::TEXTURE_CUBE_MAP_SEAMLESS);
            }
        }
    }
}
