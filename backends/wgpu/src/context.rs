//! The device: adapter choice, limits, error capture, read-back and pass timing.
//!
//! Every GPU failure becomes a typed [`RenderError`] with a message that says
//! what to do, never a panic or a hang: [`RenderError::NoAdapter`],
//! [`RenderError::GpuUnsupported`], [`RenderError::OutOfMemory`] and
//! [`RenderError::Validation`] (caught by error scopes around each pass),
//! [`RenderError::DeviceLost`] (recorded by a callback),
//! [`RenderError::LimitExceeded`], and [`RenderError::Backend`] for the rest
//! (every wait on the GPU has a timeout).

use std::any::Any;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

use subcone_scene::{PassTiming, RenderError, TimingSource};

/// Longest a single pass may run before the render is abandoned. Lavapipe
/// renders a 1280×720 SSAA16 frame in seconds; a minute means a hang.
pub const PASS_TIMEOUT: Duration = Duration::from_secs(300);

const BACKEND: &str = "wgpu";

/// The error for no adapter: names the fix.
pub const NO_ADAPTER: &str = "no GPU adapter found. Install a Vulkan driver \
    (on Debian or Ubuntu: `apt-get install libvulkan1 mesa-vulkan-drivers` for the \
    software driver, lavapipe) or select another API with WGPU_BACKEND=vulkan|metal|dx12";

/// Whether a device's GPU timestamps time its passes, and why not when they
/// do not. Both timestamp features are needed (the backend writes
/// timestamps between passes in an encoder). A software adapter (lavapipe,
/// WARP, SwiftShader) runs the shaders on this CPU: the wall time from
/// submission to completion is what the pass costs, and lavapipe's emulated
/// timestamps were seen to report 20–80 µs for multi-millisecond compute
/// passes once a render pass had run in the process. Timestamps are used on
/// hardware adapters only.
pub fn timestamp_trust(info: &wgpu::AdapterInfo, features: wgpu::Features) -> (bool, &'static str) {
    let want = wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS;
    if info.device_type == wgpu::DeviceType::Cpu {
        (false, "software adapter: its timestamps are not trusted")
    } else if !features.contains(want) {
        (
            false,
            "the device lacks TIMESTAMP_QUERY and TIMESTAMP_QUERY_INSIDE_ENCODERS",
        )
    } else {
        (true, "")
    }
}

pub(crate) fn err(reason: impl Into<String>) -> RenderError {
    RenderError::Backend {
        backend: BACKEND,
        reason: reason.into(),
    }
}

/// A wgpu device and queue with what subcone needs to know about them.
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's name, driver and API.
    pub info: wgpu::AdapterInfo,
    /// Passes are timed by GPU timestamps (else on the CPU, from submission
    /// to completion: see [`GpuContext::timing_source`]).
    pub timestamps: bool,
    /// Why timestamps are not used, when they are not.
    no_timestamps: &'static str,
    lost: Arc<Mutex<Option<String>>>,
    /// Objects built for this device and reused across frames (compiled
    /// pipelines, uploaded scenes), by typed key ([`CacheKey`]).
    pub(crate) cache: Mutex<DeviceCache>,
}

/// The key of an object kept per device: a struct per kind of object, holding
/// everything the object is built from and compared by value, so that two
/// kinds never share an entry and two keys of a kind find one object only
/// when they are equal (not merely when their hashes are).
pub(crate) trait CacheKey: std::hash::Hash + Eq + Send + Sync + 'static {
    /// The object the key finds.
    type Value: Send + Sync + 'static;
}

/// The per-device cache: one map per key type, `HashMap<K, Arc<K::Value>>`,
/// found by the key type's `TypeId`.
#[derive(Default)]
pub(crate) struct DeviceCache {
    maps: HashMap<std::any::TypeId, Box<dyn Any + Send + Sync>>,
    entries: usize,
}

impl DeviceCache {
    /// Most entries kept: past them the cache starts afresh (scenes and
    /// pipelines are few in practice, and a long-running process rendering
    /// many would otherwise grow it).
    const MAX_ENTRIES: usize = 64;

    fn get<K: CacheKey>(&self, key: &K) -> Option<Arc<K::Value>> {
        let map = self.maps.get(&std::any::TypeId::of::<K>())?;
        map.downcast_ref::<HashMap<K, Arc<K::Value>>>()?
            .get(key)
            .cloned()
    }

    fn insert<K: CacheKey>(&mut self, key: K, value: Arc<K::Value>) {
        if self.entries >= Self::MAX_ENTRIES {
            *self = DeviceCache::default();
        }
        let map = self
            .maps
            .entry(std::any::TypeId::of::<K>())
            .or_insert_with(|| Box::new(HashMap::<K, Arc<K::Value>>::new()));
        // The map under K's TypeId was made here, as K's.
        if let Some(map) = map.downcast_mut::<HashMap<K, Arc<K::Value>>>() {
            if map.insert(key, value).is_none() {
                self.entries += 1;
            }
        }
    }
}

impl std::fmt::Debug for GpuContext {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuContext")
            .field("adapter", &self.info.name)
            .field("backend", &self.info.backend)
            .field("timestamps", &self.timestamps)
            .finish()
    }
}

impl GpuContext {
    /// Open the first adapter of the APIs in `WGPU_BACKEND`, or of Vulkan,
    /// Metal and DX12 when it is unset. GL is never picked implicitly: wgpu
    /// would fall back to it silently, and GL cannot render to `Rgba32Float`.
    pub fn new() -> Result<Self, RenderError> {
        let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backends;
        desc.flags = wgpu::InstanceFlags::default().with_env();
        let instance = wgpu::Instance::new(desc);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .map_err(|e| RenderError::NoAdapter {
            backend: BACKEND,
            reason: format!("{NO_ADAPTER} ({e})"),
        })?;
        let info = adapter.get_info();
        let want =
            wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS;
        let features = adapter.features() & want;
        // Requested wherever the adapter has them (a host of the same device
        // may use them); used only where `timestamp_trust` says so.
        let (timestamps, no_timestamps) = timestamp_trust(&info, features);
        // The defaults (e.g. 128 MiB storage bindings, 8 storage buffers per
        // stage) are too small for fat G-buffers and large BVHs: ask for all
        // the adapter has.
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("subcone"),
            required_features: features,
            required_limits: limits,
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| RenderError::GpuUnsupported {
            backend: BACKEND,
            reason: format!("cannot open a device on {}: {e}", info.name),
        })?;
        let lost = Arc::new(Mutex::new(None));
        let sink = lost.clone();
        device.set_device_lost_callback(move |reason, message| {
            *sink.lock().unwrap_or_else(|e| e.into_inner()) =
                Some(format!("device lost ({reason:?}): {message}"));
        });
        // Errors outside our scopes must not abort the process (wgpu's
        // default handler panics); they are reported by the next check.
        let uncaptured = lost.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            let mut slot = uncaptured.lock().unwrap_or_else(|e| e.into_inner());
            if slot.is_none() {
                *slot = Some(format!("uncaptured GPU error: {e}"));
            }
        }));
        Ok(GpuContext {
            device,
            queue,
            info,
            timestamps,
            no_timestamps,
            lost,
            cache: Mutex::new(DeviceCache::default()),
        })
    }

    /// Wrap the host's own device and queue (an engine that embeds subcone).
    ///
    /// Unlike [`GpuContext::new`], this installs no callback: the host's
    /// device-lost and uncaptured-error handlers stay the host's (a library
    /// never takes over its caller's error handling). Errors inside subcone's
    /// passes are still caught by the error scopes around each pass
    /// ([`GpuContext::scoped`]); device loss shows up as the failure of the
    /// next pass or wait, not through [`GpuContext::check_lost`]. Passes are
    /// timed by GPU timestamps when the host opened the device with
    /// `TIMESTAMP_QUERY` and `TIMESTAMP_QUERY_INSIDE_ENCODERS` on a hardware
    /// adapter, else by the wall clock ([`GpuContext::timing_source`]).
    ///
    /// The renderers need more than wgpu's default limits (the triangle
    /// passes bind more than 8 storage buffers per stage): open the device
    /// with the adapter's own limits (`adapter.limits()`), as
    /// [`GpuContext::new`] does. On a device with too few, a render fails
    /// with a [`RenderError`] naming the limit.
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue) -> Self {
        let info = device.adapter_info();
        let (timestamps, no_timestamps) = timestamp_trust(&info, device.features());
        GpuContext {
            device,
            queue,
            info,
            timestamps,
            no_timestamps,
            lost: Arc::new(Mutex::new(None)),
            cache: Mutex::new(DeviceCache::default()),
        }
    }

    /// The object cached under `key` on this device.
    pub(crate) fn cached<K: CacheKey>(&self, key: &K) -> Option<Arc<K::Value>> {
        let cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        cache.get(key)
    }

    /// The object cached under `key` on this device, made by `make` (and
    /// kept) when there is none. The cache is not locked while `make` runs.
    pub(crate) fn cached_or_insert<K: CacheKey>(
        &self,
        key: K,
        make: impl FnOnce(&K) -> Result<K::Value, RenderError>,
    ) -> Result<Arc<K::Value>, RenderError> {
        if let Some(v) = self.cached(&key) {
            return Ok(v);
        }
        let v = Arc::new(make(&key)?);
        self.cache_insert(key, v.clone());
        Ok(v)
    }

    /// Keep `value` for this device under `key` (at most
    /// [`DeviceCache::MAX_ENTRIES`] objects).
    pub(crate) fn cache_insert<K: CacheKey>(&self, key: K, value: Arc<K::Value>) {
        let mut cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        cache.insert(key, value);
    }

    /// One context per process, opened on first use. Tests and the CLI share
    /// it: opening a device costs far more than a small render.
    pub fn shared() -> Result<Arc<GpuContext>, RenderError> {
        static SHARED: OnceLock<Result<Arc<GpuContext>, RenderError>> = OnceLock::new();
        match SHARED.get_or_init(|| GpuContext::new().map(Arc::new)) {
            Ok(ctx) => Ok(ctx.clone()),
            // Opening fails with one of these two; anything else keeps its text.
            Err(RenderError::NoAdapter { reason, .. }) => Err(RenderError::NoAdapter {
                backend: BACKEND,
                reason: reason.clone(),
            }),
            Err(RenderError::GpuUnsupported { reason, .. }) => Err(RenderError::GpuUnsupported {
                backend: BACKEND,
                reason: reason.clone(),
            }),
            Err(e) => Err(err(e.to_string())),
        }
    }

    /// A one-line description, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Mesa 22.3.6)`.
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {} {})",
            self.info.name, self.info.backend, self.info.driver, self.info.driver_info
        )
    }

    /// The error recorded by device loss or an uncaptured error, if any.
    pub fn check_lost(&self) -> Result<(), RenderError> {
        match self.lost.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
            Some(m) => Err(RenderError::DeviceLost {
                backend: BACKEND,
                reason: m.clone(),
            }),
            None => Ok(()),
        }
    }

    /// Refuse a texture (or storage image) of `width × height` beyond the
    /// device's limits, with a message naming the limit.
    pub fn check_texture_size(&self, width: u32, height: u32) -> Result<(), RenderError> {
        let max = self.device.limits().max_texture_dimension_2d;
        if width > max || height > max {
            return Err(RenderError::LimitExceeded {
                backend: BACKEND,
                what: format!("a {width}x{height} image"),
                limit: "max_texture_dimension_2d",
                requested: u64::from(width.max(height)),
                max: u64::from(max),
            });
        }
        Ok(())
    }

    /// Refuse a storage buffer of `bytes` beyond the device's limits.
    pub fn check_buffer_size(&self, what: &str, bytes: u64) -> Result<(), RenderError> {
        let l = self.device.limits();
        let max = l.max_storage_buffer_binding_size.min(l.max_buffer_size);
        if bytes > max {
            return Err(RenderError::LimitExceeded {
                backend: BACKEND,
                what: what.to_string(),
                limit: "max_storage_buffer_binding_size",
                requested: bytes,
                max,
            });
        }
        Ok(())
    }

    /// Run `f`, which records and submits GPU work, inside validation and
    /// out-of-memory error scopes; any error becomes a `RenderError`.
    pub fn scoped<T>(&self, what: &str, f: impl FnOnce() -> T) -> Result<T, RenderError> {
        self.check_lost()?;
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let out = f();
        let v = pollster::block_on(validation.pop());
        let o = pollster::block_on(oom.pop());
        if let Some(e) = o {
            return Err(RenderError::OutOfMemory {
                backend: BACKEND,
                what: what.to_string(),
                reason: e.to_string(),
            });
        }
        if let Some(e) = v {
            return Err(RenderError::Validation {
                backend: BACKEND,
                what: what.to_string(),
                reason: e.to_string(),
            });
        }
        self.check_lost()?;
        Ok(out)
    }

    /// Wait for all submitted work, at most [`PASS_TIMEOUT`].
    pub fn wait(&self, what: &str) -> Result<(), RenderError> {
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index: None,
                timeout: Some(PASS_TIMEOUT),
            })
            .map_err(|e| err(format!("{what}: waiting for the GPU failed: {e}")))?;
        self.check_lost()
    }

    /// A `width × height` 2D texture of one sample, one layer and one mip
    /// level: the shape of every per-frame texture the passes exchange.
    pub(crate) fn frame_texture(
        &self,
        label: &'static str,
        (width, height): (u32, u32),
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> wgpu::Texture {
        self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    }

    /// How this context times its passes: [`TimingSource::GpuTimestamps`]
    /// where the device has trusted timestamps, else
    /// [`TimingSource::GpuWallClock`] saying why not.
    pub fn timing_source(&self) -> TimingSource {
        if self.timestamps {
            TimingSource::GpuTimestamps
        } else {
            TimingSource::GpuWallClock {
                why: self.no_timestamps,
            }
        }
    }

    /// Record one pass with `record`, submit it, wait for it and time it: on
    /// the GPU with timestamps where the adapter has them, else on the CPU
    /// from submission to completion. The timing is pushed onto `timings`.
    pub fn timed_pass(
        &self,
        name: &'static str,
        timings: &mut Vec<PassTiming>,
        record: impl FnOnce(&mut wgpu::CommandEncoder),
    ) -> Result<(), RenderError> {
        let queries = self.timestamps.then(|| {
            let set = self.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamp resolve"),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (set, resolve)
        });
        let start = Instant::now();
        let resolve = self.scoped(name, || {
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(name) });
            if let Some((set, _)) = &queries {
                encoder.write_timestamp(set, 0);
            }
            record(&mut encoder);
            if let Some((set, resolve)) = &queries {
                encoder.write_timestamp(set, 1);
                encoder.resolve_query_set(set, 0..2, resolve, 0);
            }
            self.queue.submit([encoder.finish()]);
            queries.as_ref().map(|q| &q.1)
        })?;
        self.wait(name)?;
        let wall = start.elapsed();
        let (time, source) = match resolve {
            Some(buf) => {
                let bytes = self.read_buffer(buf, 0, 16)?;
                let t: &[u64] = bytemuck::cast_slice(&bytes);
                let ns =
                    t[1].saturating_sub(t[0]) as f64 * self.queue.get_timestamp_period() as f64;
                // Some drivers report zeros; the wall time is then the honest figure.
                if ns > 0.0 {
                    (Duration::from_nanos(ns as u64), TimingSource::GpuTimestamps)
                } else {
                    (
                        wall,
                        TimingSource::GpuWallClock {
                            why: "the pass's timestamps read zero",
                        },
                    )
                }
            }
            None => (wall, self.timing_source()),
        };
        timings.push(PassTiming { name, time, source });
        Ok(())
    }

    /// Copy `size` bytes at `offset` of `buffer` (which needs `COPY_SRC`) to
    /// the CPU.
    pub fn read_buffer(
        &self,
        buffer: &wgpu::Buffer,
        offset: u64,
        size: u64,
    ) -> Result<Vec<u8>, RenderError> {
        self.read_back(
            "read-back",
            size,
            |encoder, staging| encoder.copy_buffer_to_buffer(buffer, offset, staging, 0, size),
            <[u8]>::to_vec,
        )
    }

    /// Read `size` bytes back to the CPU: `copy` records their copy into a
    /// new mappable buffer, which is submitted, mapped and waited for, and
    /// `read` takes the mapped bytes. `what` labels the objects and the
    /// errors.
    pub(crate) fn read_back<T>(
        &self,
        what: &str,
        size: u64,
        copy: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::Buffer),
        read: impl FnOnce(&[u8]) -> T,
    ) -> Result<T, RenderError> {
        let staging = self.scoped(what, || {
            let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(what),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(what) });
            copy(&mut encoder, &staging);
            self.queue.submit([encoder.finish()]);
            staging
        })?;
        let (tx, rx) = std::sync::mpsc::channel();
        staging.map_async(wgpu::MapMode::Read, .., move |r| {
            let _ = tx.send(r);
        });
        self.wait(what)?;
        match rx.recv_timeout(Duration::from_secs(1)) {
            Ok(Ok(())) => {}
            Ok(Err(e)) => return Err(err(format!("{what} failed: {e}"))),
            Err(_) => return Err(err(format!("{what} did not complete"))),
        }
        let bytes = staging
            .get_mapped_range(..)
            .map_err(|e| err(format!("{what} failed: {e}")))?;
        let out = read(&bytes);
        drop(bytes);
        staging.unmap();
        Ok(out)
    }
}

#[cfg(test)]
mod cache_tests {
    use super::*;

    /// Two kinds of key with the same contents (and so the same hash).
    #[derive(PartialEq, Eq, Hash)]
    struct Pipeline(u64);
    impl CacheKey for Pipeline {
        type Value = &'static str;
    }
    #[derive(PartialEq, Eq, Hash)]
    struct Scene(u64);
    impl CacheKey for Scene {
        type Value = u32;
    }

    #[test]
    fn keys_of_two_kinds_never_share_an_entry() {
        let mut c = DeviceCache::default();
        c.insert(Pipeline(7), Arc::new("pipeline"));
        assert_eq!(c.get(&Scene(7)), None);
        c.insert(Scene(7), Arc::new(3));
        assert_eq!(c.get(&Pipeline(7)).as_deref(), Some(&"pipeline"));
        assert_eq!(c.get(&Scene(7)).as_deref(), Some(&3));
        assert_eq!(c.get(&Pipeline(8)), None);
        assert_eq!(c.entries, 2);
    }

    #[test]
    fn the_cache_is_bounded() {
        let mut c = DeviceCache::default();
        for i in 0..(DeviceCache::MAX_ENTRIES as u64 + 10) {
            c.insert(Scene(i), Arc::new(i as u32));
            assert!(c.entries <= DeviceCache::MAX_ENTRIES);
        }
        // The newest survives the restart; a replaced key is not counted twice.
        let last = DeviceCache::MAX_ENTRIES as u64 + 9;
        assert_eq!(c.get(&Scene(last)).as_deref(), Some(&(last as u32)));
        let before = c.entries;
        c.insert(Scene(last), Arc::new(0));
        assert_eq!(c.entries, before);
    }
}
