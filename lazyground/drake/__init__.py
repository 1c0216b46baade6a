"""The Drake side: scene → plant + SceneGraph, collision checking, IK goal sampling."""
