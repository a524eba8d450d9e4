// caoLineGridMap.glsl - a world point or direction in the lines' grid
// (LineGridMap, caoGPULayout.h), in double, as the CPU's ToVoxels and
// ToGridDirection (caoLineAO.cxx) map it; shared by the voxelization and
// the G-buffer.

/// A world direction in the grid's frame (cao::BitGrid::ToGrid).
dvec3 GridDirection(LineGridMap m, dvec3 x)
{
  return dvec3(dot(m.rows[0].xyz, x), dot(m.rows[1].xyz, x), dot(m.rows[2].xyz, x));
}

/// A world point in voxel units (the grid's frame, its origin at 0).
dvec3 GridVoxels(LineGridMap m, dvec3 x)
{
  return (GridDirection(m, x) - dvec3(m.rows[0].w, m.rows[1].w, m.rows[2].w)) / m.voxel.x;
}
