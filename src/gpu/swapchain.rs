//! Window surface and swapchain (for the viewer): owns the surface, the swapchain and its
//! images, and per frame in flight an acquire semaphore beside the [`FrameRing`]'s command
//! buffer and fence; recreated on resize. A frame is recorded by the caller into a command
//! buffer that ends by writing the acquired image. With `FRAMES_IN_FLIGHT` frames in flight the
//! CPU records a frame while the GPU runs the one before; a frame waits only for the fence of
//! the frame that last used its slot.

use std::sync::Arc;

use ash::vk;
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};

use super::{Context, FrameRing, FRAMES_IN_FLIGHT};
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
    /// Per frame in flight: its commands and fence, and (`image_available`, by the ring's slot)
    /// the semaphore its acquired image signals.
    ring: FrameRing,
    image_available: Vec<vk::Semaphore>,
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
        let ring = match FrameRing::new(ctx, FRAMES_IN_FLIGHT) {
            Ok(r) => r,
            Err(e) => {
                unsafe { surface_loader.destroy_surface(surface, None) };
                return Err(e);
            }
        };
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
            ring,
            image_available: Vec::new(),
            render_finished: Vec::new(),
        };
        for _ in 0..FRAMES_IN_FLIGHT {
            let sem =
                unsafe { d.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }.vk("vkCreateSemaphore")?;
            s.image_available.push(sem);
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
        self.ring.wait_idle()
    }

    /// Acquires an image, records `record(cmd, image)` (which must leave the image in
    /// PRESENT_SRC_KHR), submits and presents. Waits first for the frame that last used this
    /// slot, `FRAMES_IN_FLIGHT` frames ago; the one after it may still be running. `record` is
    /// not called when the swapchain is out of date before acquiring.
    pub fn frame(&mut self, record: impl FnOnce(vk::CommandBuffer, vk::Image)) -> Result<FrameOutcome> {
        self.ring.wait_slot()?;
        let acquired = self.image_available[self.ring.slot()];
        // Acquire before the fence is reset: an out-of-date swapchain leaves the slot signalled.
        let index = match unsafe { self.loader.acquire_next_image(self.raw, u64::MAX, acquired, vk::Fence::null()) } {
            Ok((i, _)) => i,
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => return Ok(FrameOutcome::OutOfDate),
            Err(result) => return Err(Error::Vulkan { call: "vkAcquireNextImageKHR", result }),
        };
        let cmd = self.ring.begin()?;
        record(cmd, self.images[index as usize]);
        let signal = [self.render_finished[index as usize]];
        self.ring.submit(&[acquired], &signal)?;
        unsafe {
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
            // The ring (fences, commands) goes with the fields, after this.
            self.loader.destroy_swapchain(self.raw, None);
            self.surface_loader.destroy_surface(self.surface, None);
        }
    }
}
