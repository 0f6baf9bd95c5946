"""The plain records every layer shares: settings, each light's plan, the frame report."""
