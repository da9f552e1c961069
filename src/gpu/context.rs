//! Vulkan instance, validation messenger, physical-device choice, logical device, queue,
//! memory allocator (gpu-allocator) and one-shot command submission. Everything else in
//! `gpu/` holds an `Arc<Context>`, so the device outlives every object made from it.

use std::ffi::{c_char, c_void, CStr, CString};
use std::mem::ManuallyDrop;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};

use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};

use super::features::{Feature, FeatureSet};
use crate::error::{Error, Result, VkContext};

/// How long a submission may run before we report the device as hung instead of waiting forever.
pub const GPU_TIMEOUT_S: u64 = 600;

/// Options for [`Context::new`].
#[derive(Clone, Debug, Default)]
pub struct ContextOptions {
    /// Enable `VK_LAYER_KHRONOS_validation` and a debug messenger that counts its messages.
    pub validation: bool,
    /// With validation, also its synchronization validation (hazards between commands, and
    /// between frames in flight).
    pub sync_validation: bool,
    /// Pick the first device whose name contains this (case-insensitive).
    pub device: Option<String>,
    /// Extra instance extensions (the window system's surface extensions, for the viewer).
    pub instance_extensions: Vec<&'static CStr>,
    /// Enable `VK_KHR_swapchain` (viewer).
    pub swapchain: bool,
}

impl ContextOptions {
    /// Validation on when asked for, or when `VCT_VALIDATION=1` is set in the environment;
    /// `VCT_VALIDATION=sync` adds synchronization validation.
    pub fn from_env(validation: bool, device: Option<String>) -> Self {
        let env = std::env::var("VCT_VALIDATION").unwrap_or_default();
        let sync_validation = env == "sync";
        ContextOptions {
            validation: validation || env == "1" || sync_validation,
            sync_validation,
            device,
            ..Default::default()
        }
    }
}

/// Counts of validation-layer messages since the context was made.
#[derive(Debug, Default)]
pub struct ValidationCounter {
    pub errors: AtomicU32,
    pub warnings: AtomicU32,
}

impl ValidationCounter {
    pub fn errors(&self) -> u32 {
        self.errors.load(Ordering::SeqCst)
    }
    pub fn warnings(&self) -> u32 {
        self.warnings.load(Ordering::SeqCst)
    }
}

unsafe extern "system" fn debug_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    ty: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    let counter = &*(user as *const ValidationCounter);
    let message = (*data).message_as_c_str().map(|m| m.to_string_lossy()).unwrap_or_default();
    let relevant =
        ty.intersects(vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE);
    if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR) {
        counter.errors.fetch_add(1, Ordering::SeqCst);
        log::error!("[vulkan] {message}");
    } else if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::WARNING) && relevant {
        counter.warnings.fetch_add(1, Ordering::SeqCst);
        log::warn!("[vulkan] {message}");
    } else {
        log::debug!("[vulkan] {message}");
    }
    vk::FALSE
}

/// One physical device as `vct devices` lists it.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    pub name: String,
    pub kind: vk::PhysicalDeviceType,
    pub driver: String,
    pub api_version: u32,
    pub features: FeatureSet,
    pub limits: vk::PhysicalDeviceLimits,
}

impl DeviceInfo {
    fn rank(&self) -> u32 {
        match self.kind {
            vk::PhysicalDeviceType::DISCRETE_GPU => 0,
            vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
            vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
            vk::PhysicalDeviceType::CPU => 3,
            _ => 4,
        }
    }

    pub fn kind_name(&self) -> &'static str {
        match self.kind {
            vk::PhysicalDeviceType::DISCRETE_GPU => "discrete",
            vk::PhysicalDeviceType::INTEGRATED_GPU => "integrated",
            vk::PhysicalDeviceType::VIRTUAL_GPU => "virtual",
            vk::PhysicalDeviceType::CPU => "cpu",
            _ => "other",
        }
    }
}

unsafe fn query_device(instance: &ash::Instance, pd: vk::PhysicalDevice) -> DeviceInfo {
    let mut driver = vk::PhysicalDeviceDriverProperties::default();
    let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut driver);
    instance.get_physical_device_properties2(pd, &mut props2);
    let props = props2.properties;
    let mut f13 = vk::PhysicalDeviceVulkan13Features::default();
    let mut f2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut f13);
    instance.get_physical_device_features2(pd, &mut f2);
    let core = f2.features;
    let exts = instance.enumerate_device_extension_properties(pd).unwrap_or_default();
    let has_ext = |name: &CStr| exts.iter().any(|e| e.extension_name_as_c_str() == Ok(name));
    let families = instance.get_physical_device_queue_family_properties(pd);
    let sparse_queue =
        queue_family_of(&families).is_some_and(|f| families[f].queue_flags.contains(vk::QueueFlags::SPARSE_BINDING));
    let features = FeatureSet {
        core,
        dynamic_rendering: f13.dynamic_rendering == vk::TRUE,
        synchronization2: f13.synchronization2 == vk::TRUE,
        no_attachment_samples: props.limits.framebuffer_no_attachments_sample_counts,
        conservative_rasterization: has_ext(ash::ext::conservative_rasterization::NAME),
        sparse: props.sparse_properties,
        sparse_queue,
    };
    let cstr = |s: Result<&CStr, _>| s.map(|c: &CStr| c.to_string_lossy().into_owned()).unwrap_or_default();
    DeviceInfo {
        name: cstr(props.device_name_as_c_str()),
        kind: props.device_type,
        driver: format!("{} {}", cstr(driver.driver_name_as_c_str()), cstr(driver.driver_info_as_c_str())),
        api_version: props.api_version,
        features,
        limits: props.limits,
    }
}

/// The queue family vct submits everything to: graphics and compute, with timestamps.
fn queue_family_of(families: &[vk::QueueFamilyProperties]) -> Option<usize> {
    families.iter().position(|f| {
        f.queue_flags.contains(vk::QueueFlags::GRAPHICS | vk::QueueFlags::COMPUTE) && f.timestamp_valid_bits > 0
    })
}

pub struct Context {
    pub entry: ash::Entry,
    pub instance: ash::Instance,
    debug: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    debug_device: Option<ash::ext::debug_utils::Device>,
    pub physical: vk::PhysicalDevice,
    pub info: DeviceInfo,
    pub device: ash::Device,
    pub queue: vk::Queue,
    pub queue_family: u32,
    command_pool: Mutex<vk::CommandPool>,
    allocator: ManuallyDrop<Mutex<Allocator>>,
    /// Bytes the live allocations asked for (the allocator's own total adds the alignment
    /// padding of where each landed, which moves with fragmentation).
    allocated: std::sync::atomic::AtomicU64,
    pub validation: Arc<ValidationCounter>,
}

impl Context {
    fn load_entry() -> Result<ash::Entry> {
        unsafe { ash::Entry::load() }.map_err(|e| Error::Loader(e.to_string()))
    }

    fn create_instance(
        entry: &ash::Entry,
        opts: &ContextOptions,
        counter: &Arc<ValidationCounter>,
    ) -> Result<(ash::Instance, bool)> {
        let app = vk::ApplicationInfo::default()
            .application_name(c"vct")
            .engine_name(c"vct")
            .api_version(vk::API_VERSION_1_3);
        let layers = unsafe { entry.enumerate_instance_layer_properties() }.vk("vkEnumerateInstanceLayerProperties")?;
        let validation_name = c"VK_LAYER_KHRONOS_validation";
        let mut layer_ptrs: Vec<*const c_char> = Vec::new();
        if opts.validation {
            if !layers.iter().any(|l| l.layer_name_as_c_str() == Ok(validation_name)) {
                return Err(Error::Loader(
                    "validation was requested but VK_LAYER_KHRONOS_validation is not installed \
                     (Debian/Ubuntu package: vulkan-validationlayers)"
                        .into(),
                ));
            }
            layer_ptrs.push(validation_name.as_ptr());
        }
        let mut ext_ptrs: Vec<*const c_char> = opts.instance_extensions.iter().map(|e| e.as_ptr()).collect();
        if opts.validation {
            ext_ptrs.push(ash::ext::debug_utils::NAME.as_ptr());
        }
        let sync = opts.validation && opts.sync_validation;
        if sync {
            ext_ptrs.push(ash::ext::validation_features::NAME.as_ptr());
        }
        let mut messenger_info = Self::messenger_info(counter);
        let enables = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        let mut features = vk::ValidationFeaturesEXT::default().enabled_validation_features(&enables);
        let mut info = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_layer_names(&layer_ptrs)
            .enabled_extension_names(&ext_ptrs);
        if opts.validation {
            info = info.push_next(&mut messenger_info);
        }
        if sync {
            info = info.push_next(&mut features);
        }
        let instance = unsafe { entry.create_instance(&info, None) }.vk("vkCreateInstance")?;
        Ok((instance, opts.validation))
    }

    fn messenger_info(counter: &Arc<ValidationCounter>) -> vk::DebugUtilsMessengerCreateInfoEXT<'static> {
        vk::DebugUtilsMessengerCreateInfoEXT::default()
            .message_severity(
                vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
                    | vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                    | vk::DebugUtilsMessageSeverityFlagsEXT::INFO,
            )
            .message_type(
                vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                    | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                    | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
            )
            .pfn_user_callback(Some(debug_callback))
            .user_data(Arc::as_ptr(counter) as *mut c_void)
    }

    /// Every physical device with its driver and features (for `vct devices`).
    pub fn list_devices() -> Result<Vec<DeviceInfo>> {
        let entry = Self::load_entry()?;
        let (instance, _) = Self::create_instance(&entry, &ContextOptions::default(), &Arc::default())?;
        let list = unsafe {
            let pds = instance.enumerate_physical_devices().vk("vkEnumeratePhysicalDevices")?;
            let l = pds.iter().map(|&pd| query_device(&instance, pd)).collect();
            instance.destroy_instance(None);
            l
        };
        Ok(list)
    }

    pub fn new(opts: &ContextOptions) -> Result<Arc<Self>> {
        let entry = Self::load_entry()?;
        let validation = Arc::new(ValidationCounter::default());
        let (instance, debug_on) = Self::create_instance(&entry, opts, &validation)?;
        let debug = if debug_on {
            let du = ash::ext::debug_utils::Instance::new(&entry, &instance);
            let m = unsafe { du.create_debug_utils_messenger(&Self::messenger_info(&validation), None) }
                .vk("vkCreateDebugUtilsMessengerEXT")?;
            Some((du, m))
        } else {
            None
        };

        // Choose: discrete, integrated, virtual, CPU, in that order, unless --device names one.
        let pds = unsafe { instance.enumerate_physical_devices() }.vk("vkEnumeratePhysicalDevices")?;
        let mut candidates: Vec<(vk::PhysicalDevice, DeviceInfo)> = pds
            .into_iter()
            .map(|pd| (pd, unsafe { query_device(&instance, pd) }))
            .filter(|(_, i)| i.api_version >= vk::API_VERSION_1_3)
            .filter(|(_, i)| opts.device.as_ref().is_none_or(|d| i.name.to_lowercase().contains(&d.to_lowercase())))
            .collect();
        candidates.sort_by_key(|(_, i)| i.rank());
        let Some((physical, info)) = candidates.into_iter().next() else {
            unsafe {
                if let Some((du, m)) = &debug {
                    du.destroy_debug_utils_messenger(*m, None);
                }
                instance.destroy_instance(None);
            }
            return Err(Error::NoDevice(opts.device.clone()));
        };
        for f in [Feature::DynamicRendering, Feature::Synchronization2] {
            if !info.features.has(f) {
                return Err(Error::MissingFeature { device: info.name.clone(), feature: f.name(), needed_by: "vct" });
            }
        }

        let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
        let queue_family = queue_family_of(&families).ok_or_else(|| Error::MissingFeature {
            device: info.name.clone(),
            feature: "a graphics+compute queue with timestamps",
            needed_by: "vct",
        })? as u32;
        let priorities = [1.0];
        let queue_info =
            [vk::DeviceQueueCreateInfo::default().queue_family_index(queue_family).queue_priorities(&priorities)];
        let mut ext_ptrs: Vec<*const c_char> = Vec::new();
        if opts.swapchain {
            ext_ptrs.push(ash::khr::swapchain::NAME.as_ptr());
        }
        if info.features.conservative_rasterization {
            ext_ptrs.push(ash::ext::conservative_rasterization::NAME.as_ptr());
        }
        let core = info.features.enabled_core();
        let mut f13 = vk::PhysicalDeviceVulkan13Features::default().dynamic_rendering(true).synchronization2(true);
        let mut f12 = vk::PhysicalDeviceVulkan12Features::default().host_query_reset(true);
        let mut f2 = vk::PhysicalDeviceFeatures2::default().features(core).push_next(&mut f13).push_next(&mut f12);
        let device_info = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queue_info)
            .enabled_extension_names(&ext_ptrs)
            .push_next(&mut f2);
        let device = unsafe { instance.create_device(physical, &device_info, None) }.vk("vkCreateDevice")?;
        let queue = unsafe { device.get_device_queue(queue_family, 0) };
        let debug_device = debug.as_ref().map(|_| ash::ext::debug_utils::Device::new(&instance, &device));

        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device: physical,
            debug_settings: Default::default(),
            buffer_device_address: false,
            allocation_sizes: Default::default(),
        })
        .map_err(|source| Error::Alloc { name: "allocator".into(), source })?;
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        let command_pool = unsafe { device.create_command_pool(&pool_info, None) }.vk("vkCreateCommandPool")?;

        Ok(Arc::new(Context {
            entry,
            instance,
            debug,
            debug_device,
            physical,
            info,
            device,
            queue,
            queue_family,
            command_pool: Mutex::new(command_pool),
            allocator: ManuallyDrop::new(Mutex::new(allocator)),
            allocated: Default::default(),
            validation,
        }))
    }

    /// Fails with an error naming the first feature in `needs` that this device lacks.
    pub fn require(&self, needs: &[Feature], needed_by: &'static str) -> Result<()> {
        match needs.iter().find(|f| !self.info.features.has(**f)) {
            Some(f) => Err(Error::MissingFeature { device: self.info.name.clone(), feature: f.name(), needed_by }),
            None => Ok(()),
        }
    }

    pub fn allocator(&self) -> std::sync::MutexGuard<'_, Allocator> {
        self.allocator.lock().expect("allocator mutex poisoned")
    }

    /// Allocates GPU memory through gpu-allocator, counting it.
    pub(crate) fn allocate(
        &self,
        desc: &gpu_allocator::vulkan::AllocationCreateDesc,
    ) -> gpu_allocator::Result<gpu_allocator::vulkan::Allocation> {
        let a = self.allocator().allocate(desc)?;
        self.allocated.fetch_add(a.size(), std::sync::atomic::Ordering::Relaxed);
        Ok(a)
    }

    /// Frees what [`Self::allocate`] gave.
    pub(crate) fn free(&self, a: gpu_allocator::vulkan::Allocation) {
        self.allocated.fetch_sub(a.size(), std::sync::atomic::Ordering::Relaxed);
        let _ = self.allocator().free(a);
    }

    /// Bytes of GPU memory the live buffers and images hold (the sizes they asked for).
    pub fn allocated_bytes(&self) -> u64 {
        self.allocated.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// Gives a Vulkan object a debug name (visible in validation messages and capture tools).
    pub fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(du) = &self.debug_device {
            let cname = CString::new(name.replace('\0', " ")).expect("no interior NUL after replace");
            let info = vk::DebugUtilsObjectNameInfoEXT::default().object_handle(handle).object_name(&cname);
            unsafe {
                let _ = du.set_debug_utils_object_name(&info);
            }
        }
    }

    /// Waits until the device has finished all submitted work.
    pub fn wait_idle(&self) -> Result<()> {
        unsafe { self.device.device_wait_idle() }.vk("vkDeviceWaitIdle")
    }

    /// Binds sparse memory on the queue (`vkQueueBindSparse`) and waits for it, so the bound
    /// blocks are resident before any later submission uses them.
    pub fn bind_sparse_and_wait(&self, what: &str, info: &vk::BindSparseInfo) -> Result<()> {
        let d = &self.device;
        unsafe {
            let fence = d.create_fence(&vk::FenceCreateInfo::default(), None).vk("vkCreateFence")?;
            let _pool = self.command_pool.lock().expect("command pool mutex poisoned");
            let r = d
                .queue_bind_sparse(self.queue, std::slice::from_ref(info), fence)
                .vk("vkQueueBindSparse")
                .and_then(|_| self.wait_fence(what, fence));
            d.destroy_fence(fence, None);
            r
        }
    }

    /// Waits for `fence`, reporting a hung device after GPU_TIMEOUT_S.
    fn wait_fence(&self, what: &str, fence: vk::Fence) -> Result<()> {
        match unsafe { self.device.wait_for_fences(&[fence], true, GPU_TIMEOUT_S * 1_000_000_000) } {
            Ok(()) => Ok(()),
            Err(vk::Result::TIMEOUT) => Err(Error::Timeout(what.to_string(), GPU_TIMEOUT_S)),
            Err(result) => Err(Error::Vulkan { call: "vkWaitForFences", result }),
        }
    }

    /// Records `record` into a fresh command buffer, submits it and waits for it to finish.
    pub fn submit_and_wait(&self, what: &str, record: impl FnOnce(vk::CommandBuffer)) -> Result<()> {
        let d = &self.device;
        let pool = self.command_pool.lock().expect("command pool mutex poisoned");
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(*pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        let cmd = unsafe { d.allocate_command_buffers(&alloc) }.vk("vkAllocateCommandBuffers")?[0];
        let result = (|| unsafe {
            let begin = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
            d.begin_command_buffer(cmd, &begin).vk("vkBeginCommandBuffer")?;
            record(cmd);
            d.end_command_buffer(cmd).vk("vkEndCommandBuffer")?;
            let fence = d.create_fence(&vk::FenceCreateInfo::default(), None).vk("vkCreateFence")?;
            let cmds = [cmd];
            let submit = [vk::SubmitInfo::default().command_buffers(&cmds)];
            let r = d
                .queue_submit(self.queue, &submit, fence)
                .vk("vkQueueSubmit")
                .and_then(|_| self.wait_fence(what, fence));
            d.destroy_fence(fence, None);
            r
        })();
        unsafe { d.free_command_buffers(*pool, &[cmd]) };
        result
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        unsafe {
            let _ = self.device.device_wait_idle();
            ManuallyDrop::drop(&mut self.allocator);
            self.device.destroy_command_pool(*self.command_pool.get_mut().unwrap(), None);
            self.device.destroy_device(None);
            if let Some((du, m)) = &self.debug {
                du.destroy_debug_utils_messenger(*m, None);
            }
            self.instance.destroy_instance(None);
        }
    }
}
