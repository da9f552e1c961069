//! GPU buffers that own their memory (gpu-allocator) and carry a debug name.

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
