//! GPU buffers that own their memory (gpu-allocator) and carry a debug name, and the
//! per-frame parameter buffer whose contents travel in the command stream (frames in flight).

use std::cell::RefCell;
use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

use super::Context;
use crate::error::{Error, Result, VkContext};

pub struct Buffer {
    ctx: Arc<Context>,
    pub raw: vk::Buffer,
    allocation: Option<Allocation>,
    pub size: u64,
    pub name: String,
}

impl Buffer {
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Self> {
        let size = size.max(4);
        let info = vk::BufferCreateInfo::default().size(size).usage(usage).sharing_mode(vk::SharingMode::EXCLUSIVE);
        let raw = unsafe { ctx.device.create_buffer(&info, None) }.vk("vkCreateBuffer")?;
        let requirements = unsafe { ctx.device.get_buffer_memory_requirements(raw) };
        let allocation = ctx
            .allocate(&AllocationCreateDesc {
                name,
                requirements,
                location,
                linear: true,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
            .map_err(|source| {
                unsafe { ctx.device.destroy_buffer(raw, None) };
                Error::Alloc { name: name.to_string(), source }
            })?;
        unsafe { ctx.device.bind_buffer_memory(raw, allocation.memory(), allocation.offset()) }
            .vk("vkBindBufferMemory")?;
        ctx.set_name(raw, name);
        Ok(Buffer { ctx: ctx.clone(), raw, allocation: Some(allocation), size, name: name.to_string() })
    }

    /// A host-visible buffer filled with `data`.
    pub fn from_slice<T: bytemuck::Pod>(
        ctx: &Arc<Context>,
        name: &str,
        usage: vk::BufferUsageFlags,
        data: &[T],
    ) -> Result<Self> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let buf = Self::new(ctx, name, bytes.len() as u64, usage, MemoryLocation::CpuToGpu)?;
        buf.write(0, bytes);
        Ok(buf)
    }

    fn mapped_ptr(&self) -> *mut u8 {
        let a = self.allocation.as_ref().expect("buffer allocation lives until drop");
        a.mapped_ptr().expect("buffer is host-visible").as_ptr() as *mut u8
    }

    /// Writes bytes into a host-visible buffer at `offset` (the GPU must not be using it).
    pub fn write(&self, offset: usize, bytes: &[u8]) {
        assert!(offset + bytes.len() <= self.size as usize, "write past the end of '{}'", self.name);
        unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), self.mapped_ptr().add(offset), bytes.len()) };
    }

    pub fn write_pod<T: bytemuck::Pod>(&self, value: &T) {
        self.write(0, bytemuck::bytes_of(value));
    }

    /// Reads a host-visible buffer.
    pub fn read(&self) -> &[u8] {
        unsafe { std::slice::from_raw_parts(self.mapped_ptr(), self.size as usize) }
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        if let Some(a) = self.allocation.take() {
            self.ctx.free(a);
        }
        unsafe { self.ctx.device.destroy_buffer(self.raw, None) };
    }
}

/// Frames the viewer keeps in flight: while the GPU runs one, the CPU records the next.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// Which of `FRAMES_IN_FLIGHT` per-frame copies of something (a query pool, a read-back) frames
/// use, in turn.
pub struct FrameSlot(std::cell::Cell<usize>);

impl Default for FrameSlot {
    fn default() -> Self {
        // The first `advance` gives copy 0.
        FrameSlot(std::cell::Cell::new(FRAMES_IN_FLIGHT - 1))
    }
}

impl FrameSlot {
    /// A new frame takes the next copy; returns it.
    pub fn advance(&self) -> usize {
        let i = (self.0.get() + 1) % FRAMES_IN_FLIGHT;
        self.0.set(i);
        i
    }

    /// The copy of the last frame (the one being recorded, or the last recorded).
    pub fn last(&self) -> usize {
        self.0.get()
    }

    /// The copy of the frame `FRAMES_IN_FLIGHT - 1` before the last: the one the next frame's
    /// fence has seen finish.
    pub fn settled(&self) -> usize {
        (self.0.get() + 1) % FRAMES_IN_FLIGHT
    }
}

/// A small buffer of per-frame parameters (uniforms, overlay text) that the host may change at
/// any time, even while earlier frames that read it are still running: the host keeps a copy,
/// and each frame's commands upload it (`vkCmdUpdateBuffer`) between barriers, so every frame
/// reads what it was recorded with without a buffer per frame in flight.
pub struct FrameBuffer {
    pub buffer: Buffer,
    contents: RefCell<Vec<u8>>,
}

impl FrameBuffer {
    /// A device-local buffer of `size` bytes (at most 65536, vkCmdUpdateBuffer's limit), zeroed.
    pub fn new(ctx: &Arc<Context>, name: &str, size: u64, usage: vk::BufferUsageFlags) -> Result<Self> {
        let size = size.next_multiple_of(4);
        assert!(size <= 65536, "'{name}' is too large to update in the command stream");
        let usage = usage | vk::BufferUsageFlags::TRANSFER_DST;
        let buffer = Buffer::new(ctx, name, size, usage, MemoryLocation::GpuOnly)?;
        Ok(FrameBuffer { buffer, contents: RefCell::new(vec![0; size as usize]) })
    }

    /// Sets bytes from `offset` on; frames recorded from now on read them.
    pub fn set(&self, offset: usize, bytes: &[u8]) {
        let mut c = self.contents.borrow_mut();
        assert!(offset + bytes.len() <= c.len(), "write past the end of '{}'", self.buffer.name);
        c[offset..offset + bytes.len()].copy_from_slice(bytes);
    }

    pub fn set_pod<T: bytemuck::Pod>(&self, value: &T) {
        self.set(0, bytemuck::bytes_of(value));
    }

    /// What frames recorded from now on read.
    pub fn contents(&self) -> Vec<u8> {
        self.contents.borrow().clone()
    }

    /// Records the upload: after every earlier command's reads (of this and earlier frames),
    /// before every later command's.
    pub fn record_upload(&self, cmd: vk::CommandBuffer) {
        let ctx = &self.buffer.ctx;
        let all = vk::PipelineStageFlags2::ALL_COMMANDS;
        let copy = vk::PipelineStageFlags2::COPY;
        let reads = vk::AccessFlags2::SHADER_READ | vk::AccessFlags2::UNIFORM_READ;
        let barrier = |src: (vk::PipelineStageFlags2, vk::AccessFlags2),
                       dst: (vk::PipelineStageFlags2, vk::AccessFlags2)| {
            let b = [vk::BufferMemoryBarrier2::default()
                .src_stage_mask(src.0)
                .src_access_mask(src.1)
                .dst_stage_mask(dst.0)
                .dst_access_mask(dst.1)
                .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                .buffer(self.buffer.raw)
                .offset(0)
                .size(vk::WHOLE_SIZE)];
            unsafe { ctx.device.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().buffer_memory_barriers(&b)) };
        };
        barrier((all, reads), (copy, vk::AccessFlags2::TRANSFER_WRITE));
        unsafe { ctx.device.cmd_update_buffer(cmd, self.buffer.raw, 0, &self.contents.borrow()) };
        barrier((copy, vk::AccessFlags2::TRANSFER_WRITE), (all, reads));
    }
}
