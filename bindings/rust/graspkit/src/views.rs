//! Read-only views of one body or one robot of a world: `world.body(i)?.name()?` instead of
//! `world.body_name(i)?`. They borrow the world, so it cannot change while one is held; change
//! it through the `World` methods.

use crate::error::Result;
use crate::world::{Pose, World};

/// A free body of a world (an obstacle or a graspable body).
#[derive(Clone, Copy)]
pub struct Body<'w> {
    world: &'w World,
    index: i32,
}

/// A robot of a world.
#[derive(Clone, Copy)]
pub struct Robot<'w> {
    world: &'w World,
    index: i32,
}

impl World {
    /// Body `index`, checked.
    pub fn body(&self, index: i32) -> Result<Body<'_>> {
        self.body_name(index)?;
        Ok(Body { world: self, index })
    }

    /// Every free body, in the world's order.
    pub fn bodies(&self) -> Result<Vec<Body<'_>>> {
        Ok((0..self.body_count()?)
            .map(|index| Body { world: self, index })
            .collect())
    }

    /// Robot `index`, checked.
    pub fn robot(&self, index: i32) -> Result<Robot<'_>> {
        self.robot_name(index)?;
        Ok(Robot { world: self, index })
    }

    /// Every robot, in the world's order.
    pub fn robots(&self) -> Result<Vec<Robot<'_>>> {
        Ok((0..self.robot_count()?)
            .map(|index| Robot { world: self, index })
            .collect())
    }
}

impl<'w> Body<'w> {
    /// Its index in the world.
    pub fn index(&self) -> i32 {
        self.index
    }
    /// Its name, unique in the world.
    pub fn name(&self) -> Result<String> {
        self.world.body_name(self.index)
    }
    /// Whether it is graspable rather than an obstacle.
    pub fn is_graspable(&self) -> Result<bool> {
        self.world.is_graspable(self.index)
    }
    /// Mass (g) and centre of gravity in its own frame (mm).
    pub fn mass(&self) -> Result<(f64, [f64; 3])> {
        self.world.mass(self.index)
    }
    /// Its pose in the world.
    pub fn pose(&self) -> Result<Pose> {
        self.world.body_pose(self.index)
    }
}

impl<'w> Robot<'w> {
    /// Its index in the world.
    pub fn index(&self) -> i32 {
        self.index
    }
    /// Its name (the robot file's stem).
    pub fn name(&self) -> Result<String> {
        self.world.robot_name(self.index)
    }
    /// Its DOF values.
    pub fn dofs(&self) -> Result<Vec<f64>> {
        self.world.dofs(self.index)
    }
    /// Its DOF ranges, (min, max).
    pub fn dof_limits(&self) -> Result<(Vec<f64>, Vec<f64>)> {
        self.world.dof_limits(self.index)
    }
    /// Its base (palm) pose.
    pub fn pose(&self) -> Result<Pose> {
        self.world.robot_pose(self.index)
    }
    /// The world pose of link `link` of chain `chain` (-1, -1: the palm).
    pub fn link_pose(&self, chain: i32, link: i32) -> Result<Pose> {
        self.world.link_pose(self.index, chain, link)
    }
    /// Every link's pose, chain by chain.
    pub fn link_poses(&self) -> Result<Vec<Vec<Pose>>> {
        let mut chains = Vec::new();
        for chain in 0..self.world.chain_count(self.index)? {
            let links = self.world.link_count(self.index, chain)?;
            chains.push(
                (0..links)
                    .map(|link| self.link_pose(chain, link))
                    .collect::<Result<Vec<_>>>()?,
            );
        }
        Ok(chains)
    }
}
