//! Window surface and swapchain (for the viewer): owns the surface, the swapchain and its
//! images, and per frame in flight a command buffer, an acquire semaphore and a fence;
//! recreated on resize. A frame is recorded by the caller into a command buffer that ends by
//! writing the acquired image. With `FRAMES_IN_FLIGHT` frames in flight the CPU records a frame
//! while the GPU runs the one before; a frame waits only for the fence of the frame that last
//! used its slot.

use std::sync::Arc;

use ash::vk;
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};

use super::{Context, FRAMES_IN_FLIGHT};
use crate::error::{Error, Result, VkContext};

pub struct Swapchain {
    ctx: Arc<Context>,
    surface_loader: ash::khr::surface::Instance,
    surface: vk::SurfaceKHR,
    loader: ash::khr::swapchain::Device,
    raw: vk::SwapchainKHR,
    pub images: Vec<vk::Image>,
    pub extent: vk::Extent2D,
    pub format: vk::Format,
    vsync: bool,
    pool: vk::CommandPool,
    /// Per frame in flight (`slot` the next): its commands, the semaphore its acquired image
    /// signals, and the fence its submission signals.
    cmds: Vec<vk::CommandBuffer>,
    image_available: Vec<vk::Semaphore>,
    in_flight: Vec<vk::Fence>,
    slot: usize,
    /// Per swapchain image: signalled by the frame that wrote it, waited on by its present.
    render_finished: Vec<vk::Semaphore>,
}

/// What became of a frame.
#[derive(Debug, PartialEq, Eq)]
pub enum FrameOutcome {
    Presented,
    /// The swapchain no longer matches the window; call [`Swapchain::recreate`].
    OutOfDate,
}

impl Swapchain {
    pub fn new(
        ctx: &Arc<Context>,
        window: &(impl HasDisplayHandle + HasWindowHandle),
        width: u32,
        height: u32,
        vsync: bool,
    ) -> Result<Self> {
        let display = window.display_handle().map_err(|e| Error::Loader(format!("no display handle: {e}")))?.as_raw();
        let handle = window.window_handle().map_err(|e| Error::Loader(format!("no window handle: {e}")))?.as_raw();
        let surface = unsafe { ash_window::create_surface(&ctx.entry, &ctx.instance, display, handle, None) }
            .vk("vkCreateSurfaceKHR")?;
        let surface_loader = ash::khr::surface::Instance::new(&ctx.entry, &ctx.instance);
        let supported =
            unsafe { surface_loader.get_physical_device_surface_support(ctx.physical, ctx.queue_family, surface) }
                .vk("vkGetPhysicalDeviceSurfaceSupportKHR")?;
        if !supported {
            unsafe { surface_loader.destroy_surface(surface, None) };
            return Err(Error::MissingFeature {
                device: ctx.info.name.clone(),
                feature: "presentation to this window",
                needed_by: "the viewer",
            });
        }
        let loader = ash::khr::swapchain::Device::new(&ctx.instance, &ctx.device);
        let d = &ctx.device;
        let pool = unsafe {
            d.create_command_pool(
                &vk::CommandPoolCreateInfo::default()
                    .queue_family_index(ctx.queue_family)
                    .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER),
                None,
            )
        }
        .vk("vkCreateCommandPool")?;
        // Everything made so far is owned by `s` (or its pool) before the next call can fail.
        let mut s = Swapchain {
            ctx: ctx.clone(),
            surface_loader,
            surface,
            loader,
            raw: vk::SwapchainKHR::null(),
            images: Vec::new(),
            extent: vk::Extent2D { width, height },
            format: vk::Format::B8G8R8A8_UNORM,
            vsync,
            pool,
            cmds: Vec::new(),
            image_available: Vec::new(),
            in_flight: Vec::new(),
            slot: 0,
            render_finished: Vec::new(),
        };
        s.cmds = unsafe {
            d.allocate_command_buffers(
                &vk::CommandBufferAllocateInfo::default()
                    .command_pool(pool)
                    .command_buffer_count(FRAMES_IN_FLIGHT as u32),
            )
        }
        .vk("vkAllocateCommandBuffers")?;
        for _ in 0..FRAMES_IN_FLIGHT {
            let sem =
                unsafe { d.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }.vk("vkCreateSemaphore")?;
            s.image_available.push(sem);
            let signalled = vk::FenceCreateInfo::default().flags(vk::FenceCreateFlags::SIGNALED);
            s.in_flight.push(unsafe { d.create_fence(&signalled, None) }.vk("vkCreateFence")?);
        }
        s.recreate(width, height)?;
        Ok(s)
    }

    /// (Re)creates the swapchain for a window of this size (clamped to what the surface allows).
    pub fn recreate(&mut self, width: u32, height: u32) -> Result<()> {
        let ctx = self.ctx.clone();
        self.wait_idle()?;
        let caps = unsafe { self.surface_loader.get_physical_device_surface_capabilities(ctx.physical, self.surface) }
            .vk("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")?;
        let formats = unsafe { self.surface_loader.get_physical_device_surface_formats(ctx.physical, self.surface) }
            .vk("vkGetPhysicalDeviceSurfaceFormatsKHR")?;
        let modes =
            unsafe { self.surface_loader.get_physical_device_surface_present_modes(ctx.physical, self.surface) }
                .vk("vkGetPhysicalDeviceSurfacePresentModesKHR")?;
        // The renderer writes gamma-encoded 8-bit colour: present it as UNORM, not sRGB.
        let format = formats
            .iter()
            .find(|f| matches!(f.format, vk::Format::B8G8R8A8_UNORM | vk::Format::R8G8B8A8_UNORM))
            .or(formats.first())
            .copied()
            .ok_or_else(|| Error::MissingFeature {
                device: ctx.info.name.clone(),
                feature: "a surface format",
                needed_by: "the viewer",
            })?;
        let mode = if self.vsync {
            vk::PresentModeKHR::FIFO
        } else {
            [vk::PresentModeKHR::MAILBOX, vk::PresentModeKHR::IMMEDIATE]
                .into_iter()
                .find(|m| modes.contains(m))
                .unwrap_or(vk::PresentModeKHR::FIFO)
        };
        let extent = if caps.current_extent.width != u32::MAX {
            caps.current_extent
        } else {
            vk::Extent2D {
                width: width.clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                height: height.clamp(caps.min_image_extent.height, caps.max_image_extent.height),
            }
        };
        let mut count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            count = count.min(caps.max_image_count);
        }
        let old = self.raw;
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(self.surface)
            .min_image_count(count)
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::COLOR_ATTACHMENT)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(vk::CompositeAlphaFlagsKHR::OPAQUE)
            .present_mode(mode)
            .clipped(true)
            .old_swapchain(old);
        self.raw = unsafe { self.loader.create_swapchain(&info, None) }.vk("vkCreateSwapchainKHR")?;
        unsafe {
            if old != vk::SwapchainKHR::null() {
                self.loader.destroy_swapchain(old, None);
            }
        }
        self.images = unsafe { self.loader.get_swapchain_images(self.raw) }.vk("vkGetSwapchainImagesKHR")?;
        // The render-finished semaphores are kept across recreations: the presentation engine
        // may still hold the last one, and a fence does not say when it lets go.
        while self.render_finished.len() < self.images.len() {
            let s = unsafe { ctx.device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }
                .vk("vkCreateSemaphore")?;
            self.render_finished.push(s);
        }
        self.extent = extent;
        self.format = format.format;
        Ok(())
    }

    /// Waits until every frame in flight has finished.
    pub fn wait_idle(&self) -> Result<()> {
        self.wait(&self.in_flight)
    }

    fn wait(&self, fences: &[vk::Fence]) -> Result<()> {
        match unsafe { self.ctx.device.wait_for_fences(fences, true, super::context::GPU_TIMEOUT_S * 1_000_000_000) } {
            Ok(()) => Ok(()),
            Err(vk::Result::TIMEOUT) => Err(Error::Timeout("viewer frame".into(), super::context::GPU_TIMEOUT_S)),
            Err(result) => Err(Error::Vulkan { call: "vkWaitForFences", result }),
        }
    }

    /// Acquires an image, records `record(cmd, image)` (which must leave the image in
    /// PRESENT_SRC_KHR), submits and presents. Waits first for the frame that last used this
    /// slot, `FRAMES_IN_FLIGHT` frames ago; the one after it may still be running. `record` is
    /// not called when the swapchain is out of date before acquiring.
    pub fn frame(&mut self, record: impl FnOnce(vk::CommandBuffer, vk::Image)) -> Result<FrameOutcome> {
        let slot = self.slot;
        self.wait(&self.in_flight[slot..slot + 1])?;
        let d = &self.ctx.device;
        let (cmd, fence, acquired) = (self.cmds[slot], self.in_flight[slot], self.image_available[slot]);
        let index = match unsafe { self.loader.acquire_next_image(self.raw, u64::MAX, acquired, vk::Fence::null()) } {
            Ok((i, _)) => i,
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => return Ok(FrameOutcome::OutOfDate),
            Err(result) => return Err(Error::Vulkan { call: "vkAcquireNextImageKHR", result }),
        };
        unsafe {
            d.reset_fences(&[fence]).vk("vkResetFences")?;
            d.begin_command_buffer(
                cmd,
                &vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT),
            )
            .vk("vkBeginCommandBuffer")?;
        }
        record(cmd, self.images[index as usize]);
        let finished = self.render_finished[index as usize];
        self.slot = (slot + 1) % FRAMES_IN_FLIGHT;
        unsafe {
            d.end_command_buffer(cmd).vk("vkEndCommandBuffer")?;
            let wait = [acquired];
            let stages = [vk::PipelineStageFlags::ALL_COMMANDS];
            let cmds = [cmd];
            let signal = [finished];
            let submit = [vk::SubmitInfo::default()
                .wait_semaphores(&wait)
                .wait_dst_stage_mask(&stages)
                .command_buffers(&cmds)
                .signal_semaphores(&signal)];
            d.queue_submit(self.ctx.queue, &submit, fence).vk("vkQueueSubmit")?;
            let swapchains = [self.raw];
            let indices = [index];
            let present =
                vk::PresentInfoKHR::default().wait_semaphores(&signal).swapchains(&swapchains).image_indices(&indices);
            match self.loader.queue_present(self.ctx.queue, &present) {
                Ok(false) => Ok(FrameOutcome::Presented),
                Ok(true) | Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(FrameOutcome::OutOfDate),
                Err(result) => Err(Error::Vulkan { call: "vkQueuePresentKHR", result }),
            }
        }
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        unsafe {
            let d = &self.ctx.device;
            let _ = d.device_wait_idle();
            for s in self.render_finished.drain(..) {
                d.destroy_semaphore(s, None);
            }
            for s in self.image_available.drain(..) {
                d.destroy_semaphore(s, None);
            }
            for f in self.in_flight.drain(..) {
                d.destroy_fence(f, None);
            }
            d.destroy_command_pool(self.pool, None);
            self.loader.destroy_swapchain(self.raw, None);
            self.surface_loader.destroy_surface(self.surface, None);
        }
    }
}
