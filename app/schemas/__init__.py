"""Request and response models (pydantic v2). Input models forbid unknown fields and non-finite numbers."""
